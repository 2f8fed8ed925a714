// §3 The container: magic, version, header, length-prefixed sections in fixed order, CRC-32.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prm/codec.h"

namespace prm::codec {

// §3.1 Magic: "PRM" followed by 0x1A.
constexpr uint8_t kMagic[4] = {'P', 'R', 'M', 0x1A};

// §3.4 Section ids: 3 and 4 are the PRM sections (§7 irregular triangles, §8-§9 patches), present together or not
// at all; 5..15 are reserved for later versions and rejected as unsupported_feature. Anything else is bad_section.
enum SectionId : uint8_t {
  kSectionConnectivity = 1,
  kSectionPositions = 2,
  kSectionIrregular = 3,
  kSectionPatches = 4,
  kFirstReservedSection = 5,
  kLastReservedSection = 15,
};
const char* section_name(uint8_t id);

// §3.3 Flags: bit 0 = the valence context of the irregular triangles (§7.3, format 1.2), bit 2 = the seam context
// of the CLERS symbols (§6.5.2, format 1.3), bit 3 = the patch contexts: bases from their references (§8.4.1) and
// the heights' sign contexts (§9.7.4, format 1.4), bit 4 = the patch grids: a grid size per patch (§8.4.2, format
// 1.5); the other bits are reserved (unsupported_feature).
constexpr uint8_t kFlagLersValence = 0x01;
constexpr uint8_t kFlagClersSeam = 0x04;
constexpr uint8_t kFlagPatchContexts = 0x08;
constexpr uint8_t kFlagPatchGrids = 0x10;
constexpr uint8_t kKnownFlags = kFlagLersValence | kFlagClersSeam | kFlagPatchContexts | kFlagPatchGrids;

// §3.3 The header fields.
struct Header {
  uint8_t version_major = kFormatMajor;
  uint8_t version_minor = kFormatMinor;
  uint8_t flags = 0;
  uint32_t vertices = 0;
  uint32_t triangles = 0;
  Frame frame;
  std::array<uint32_t, 3> bbox_min{};
  std::array<uint32_t, 3> bbox_max{};
};

struct Section {
  uint8_t id = 0;
  uint64_t offset = 0;  // payload offset in the stream
  uint64_t size = 0;
};

struct Container {
  Header header;
  uint64_t header_bytes = 0;  // magic, version and header fields
  std::vector<Section> sections;
  uint32_t crc = 0;
  const Section* find(uint8_t id) const {
    for (const Section& s : sections)
      if (s.id == id) return &s;
    return nullptr;
  }
};

// §3 Parses and validates the container (not the section payloads).
Status read_container(const uint8_t* data, size_t size, Container& out);

// Writes a stream: header, then (id, payload) sections in the given (increasing id) order, then the CRC.
std::vector<uint8_t> write_container(const Header& header, const std::vector<std::pair<uint8_t, const std::vector<uint8_t>*>>& sections,
                                     size_t* header_bytes);

}  // namespace prm::codec
