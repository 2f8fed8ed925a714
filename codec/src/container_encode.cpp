// §3 The container, encoder side. The decoder side is container_decode.cpp.
#include "container.h"
#include "crc32.h"
#include "stream_writer.h"

namespace prm::codec {

std::vector<uint8_t> write_container(const Header& h,
                                     const std::vector<std::pair<uint8_t, const std::vector<uint8_t>*>>& sections,
                                     size_t* header_bytes) {
  StreamWriter w;
  w.bytes(kMagic, 4);  // §3.1
  w.u8(h.version_major);  // §3.2
  w.u8(h.version_minor);
  w.u8(h.flags);  // §3.3
  w.u8(static_cast<uint8_t>(h.frame.bits));
  w.varint(h.vertices);
  w.varint(h.triangles);
  for (int k = 0; k < 3; ++k) w.f64(h.frame.origin[k]);
  w.f64(h.frame.step);
  for (int k = 0; k < 3; ++k) w.varint(h.bbox_min[k]);
  for (int k = 0; k < 3; ++k) w.varint(h.bbox_max[k] - h.bbox_min[k]);
  if (header_bytes) *header_bytes = w.size();
  for (const auto& s : sections) {  // §3.4
    w.u8(s.first);
    w.varint(static_cast<uint32_t>(s.second->size()));
    w.bytes(*s.second);
  }
  w.u32(crc32(w.buffer().data(), w.size()));  // §3.5
  return std::move(w.buffer());
}

}  // namespace prm::codec
