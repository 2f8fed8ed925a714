#include "codec_cli_util.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "prm/error.h"

namespace prm::cli {

std::vector<uint8_t> read_file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError("cannot open '" + path + "': " + std::strerror(errno));
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) throw IoError("cannot read '" + path + "'");
  return bytes;
}

void write_file_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError("cannot create '" + path + "': " + std::strerror(errno));
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw IoError("cannot write '" + path + "'");
}

std::string describe(const codec::Status& s) {
  std::string out = codec::error_name(s.error);
  if (s.byte_offset) out += " at byte " + std::to_string(s.byte_offset);
  if (s.spec_section && *s.spec_section) out += std::string(" (spec §") + s.spec_section + ")";
  if (!s.message.empty()) out += ": " + s.message;
  return out;
}

}  // namespace prm::cli
