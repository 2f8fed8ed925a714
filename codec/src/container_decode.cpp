// §3 The container, decoder side: everything is checked against the bytes present before it is used.
#include <cmath>
#include <cstring>
#include <string>

#include "container.h"
#include "crc32.h"
#include "limits.h"
#include "status.h"
#include "stream_reader.h"

namespace prm::codec {

const char* section_name(uint8_t id) {
  switch (id) {
    case kSectionConnectivity:
      return "connectivity";
    case kSectionPositions:
      return "positions";
    case kSectionIrregular:
      return "irregular_triangles";
    case kSectionPatches:
      return "patches";
    default:
      return id >= kFirstReservedSection && id <= kLastReservedSection ? "reserved" : "unknown";
  }
}

Status read_container(const uint8_t* data, size_t size, Container& out) {
  out = Container{};
  // §3.1 Magic.
  if (size < 4 || std::memcmp(data, kMagic, 4) != 0)
    return make_status(size < 4 ? Error::truncated : Error::bad_magic, "3.1", 0, "not a PRM stream (bad magic)");
  // §3.7 Order of checks: each field is checked as soon as it is read; a field that cannot be read whole is
  // truncated (or, for a varint, bad_section once a byte makes it malformed, §1.3).
  StreamReader r(data, size);
  r.bytes(4);
  // §3.2 Version.
  Header& h = out.header;
  h.version_major = r.u8();
  if (r.failed()) return make_status(Error::truncated, "3.2", r.error_offset(), "stream ends in the version");
  if (h.version_major != kFormatMajor)
    return make_status(Error::unsupported_version, "3.2", 4,
                       "format version " + std::to_string(h.version_major) + ".x (this decoder reads " +
                           std::to_string(kFormatMajor) + ".x)");
  h.version_minor = r.u8();
  if (r.failed()) return make_status(Error::truncated, "3.2", r.error_offset(), "stream ends in the version");
  // §3.5 CRC-32 of everything before the last 4 bytes, before any other field is used.
  if (size < 4 + 2 + 4) return make_status(Error::truncated, "3.5", size, "stream too short for its CRC");
  {
    const uint8_t* c = data + size - 4;
    out.crc = uint32_t{c[0]} | uint32_t{c[1]} << 8 | uint32_t{c[2]} << 16 | uint32_t{c[3]} << 24;
    if (crc32(data, size - 4) != out.crc)
      return make_status(Error::crc_mismatch, "3.5", size - 4, "CRC-32 mismatch: the stream is corrupt or truncated");
  }
  StreamReader body(data, size - 4);
  body.bytes(6);
  const auto ended = [&body](const char* section, const char* where) {
    if (body.error() == Error::bad_section)
      return make_status(Error::bad_section, "1.3", body.error_offset(), std::string("malformed varint in ") + where);
    return make_status(body.error(), section, body.error_offset(), std::string("stream ends in ") + where);
  };
  // §3.3 Header, field by field.
  h.flags = body.u8();
  if (body.failed()) return ended("3.3", "the header");
  if ((h.flags & ~kKnownFlags) != 0)
    return make_status(Error::unsupported_feature, "3.3", 6,
                       "Flags " + std::to_string(h.flags) + " (only bits 0, 2, 3 and 4 are defined)");
  h.frame.bits = body.u8();
  if (body.failed()) return ended("3.3", "the header");
  if (h.frame.bits < kMinPositionBits || h.frame.bits > kMaxPositionBits)
    return make_status(Error::bad_header, "3.3", 7, "Position_Bits " + std::to_string(h.frame.bits) + " not in 8..20");
  h.vertices = body.varint();
  if (body.failed()) return ended("3.3", "the header");
  h.triangles = body.varint();
  if (body.failed()) return ended("3.3", "the header");
  if ((h.vertices == 0) != (h.triangles == 0))
    return make_status(Error::bad_header, "3.3", body.offset(), "vertices without triangles or vice versa");
  for (int k = 0; k < 3; ++k) {
    h.frame.origin[k] = body.f64();
    if (body.failed()) return ended("3.3", "the header");
    if (!std::isfinite(h.frame.origin[k]))
      return make_status(Error::bad_header, "3.3", body.offset() - 8, "Origin is not finite");
  }
  h.frame.step = body.f64();
  if (body.failed()) return ended("3.3", "the header");
  if (!std::isfinite(h.frame.step) || !(h.frame.step > 0))
    return make_status(Error::bad_header, "3.3", body.offset() - 8, "Step is not finite and positive");
  for (int k = 0; k < 3; ++k) {
    h.bbox_min[k] = body.varint();
    if (body.failed()) return ended("3.3", "the header");
  }
  const uint64_t qmax = (uint64_t{1} << h.frame.bits) - 1;
  for (int k = 0; k < 3; ++k) {
    const uint32_t extent = body.varint();
    if (body.failed()) return ended("3.3", "the header");
    if (uint64_t{h.bbox_min[k]} + extent > qmax)
      return make_status(Error::bad_header, "3.3", body.offset(), "bounding box outside 0..2^Position_Bits-1");
    h.bbox_max[k] = h.bbox_min[k] + extent;
  }
  out.header_bytes = body.offset();
  // §3.4 Sections until the CRC, in increasing id order: the id is checked before the length is read.
  int last = 0;
  while (body.remaining() > 0) {
    const uint64_t at = body.offset();
    const uint8_t id = body.u8();
    if (id >= kFirstReservedSection && id <= kLastReservedSection)
      return make_status(Error::unsupported_feature, "3.4", at,
                         "section " + std::to_string(id) + " is reserved for a later version");
    if (id != kSectionConnectivity && id != kSectionPositions && id != kSectionIrregular && id != kSectionPatches)
      return make_status(Error::bad_section, "3.4", at, "unknown section id " + std::to_string(id));
    if (id <= last)
      return make_status(Error::bad_section, "3.4", at, "section " + std::to_string(id) + " repeated or out of order");
    last = id;
    const uint32_t length = body.varint();
    if (body.failed()) return ended("3.4", "a section header");
    if (length > body.remaining())
      return make_status(Error::truncated, "3.4", at,
                         "section " + std::string(section_name(id)) + " is " + std::to_string(length) +
                             " bytes but only " + std::to_string(body.remaining()) + " remain");
    Section s;
    s.id = id;
    s.offset = body.offset();
    s.size = length;
    body.bytes(length);
    out.sections.push_back(s);
  }
  for (uint8_t id : {kSectionConnectivity, kSectionPositions})
    if (!out.find(id))
      return make_status(Error::bad_section, "3.4", size - 4,
                         std::string("the ") + section_name(id) + " section is missing");
  if ((out.find(kSectionIrregular) != nullptr) != (out.find(kSectionPatches) != nullptr))
    return make_status(Error::bad_section, "3.4", size - 4, "the irregular_triangles and patches sections come together");
  return ok_status();
}

}  // namespace prm::codec
