// EXT_meshopt_compression bufferViews (KhronosGroup/glTF extensions/2.0/Vendor/EXT_meshopt_compression) decoded
// with meshoptimizer's own decoders (Debian libmeshoptimizer-dev).
#include <meshoptimizer.h>

#include "prm/error.h"
#include "prm/gltf/decompress.h"

namespace prm::gltf {
namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr size_t kMaxExpansion = 64;  // decoded bytes per compressed byte, at most (decode_meshopt_views)

[[noreturn]] void fail(const Document& doc, const std::string& what) { throw InputError(doc.path + ": " + what); }

}  // namespace

size_t decode_meshopt_views(Document& doc) {
  if (!doc.json.contains("bufferViews")) return 0;
  size_t decoded = 0;
  for (size_t i = 0; i < doc.json["bufferViews"].size(); ++i) {
    nlohmann::json& view = doc.json["bufferViews"][i];
    if (!view.contains("extensions") || !view["extensions"].contains(kMeshopt)) continue;
    const nlohmann::json ext = view["extensions"][kMeshopt];
    const std::string where = "bufferViews[" + std::to_string(i) + "].extensions." + kMeshopt;
    for (const char* key : {"buffer", "byteLength", "byteStride", "count"})
      if (!ext.contains(key) || !ext[key].is_number_unsigned()) fail(doc, where + "." + key + " is missing or not a non-negative integer");
    if (ext.contains("byteOffset") && !ext["byteOffset"].is_number_unsigned())
      fail(doc, where + ".byteOffset is not a non-negative integer");
    for (const char* key : {"mode", "filter"})
      if (ext.contains(key) && !ext[key].is_string()) fail(doc, where + "." + key + " is not a string");
    const size_t buffer = ext["buffer"].get<size_t>(), offset = ext.value("byteOffset", size_t{0}),
                 length = ext["byteLength"].get<size_t>(), stride = ext["byteStride"].get<size_t>(),
                 count = ext["count"].get<size_t>();
    const std::string mode = ext.value("mode", std::string());
    const std::string filter = ext.value("filter", std::string("NONE"));
    if (buffer >= doc.buffers.size() || offset > doc.buffers[buffer].size() || length > doc.buffers[buffer].size() - offset)
      fail(doc, where + ": byteOffset + byteLength reach past the end of buffers[" + std::to_string(buffer) + "]");
    if (stride == 0 || stride > 256 || count > (size_t{1} << 28))
      fail(doc, where + ": byteStride " + std::to_string(stride) + " / count " + std::to_string(count) + " out of range");
    // No meshopt codec expands its input more than 64 times (the vertex codec's densest block: a 2-bit header per 16
    // zero bytes; the index codecs write at least a byte per triangle or index): a larger claim is refused before
    // count x byteStride bytes are allocated for it.
    if (count * stride > kMaxExpansion * length)
      fail(doc, where + ": count x byteStride = " + std::to_string(count * stride) + " bytes from " +
                    std::to_string(length) + " compressed bytes, more than meshopt's codecs expand to (" +
                    std::to_string(kMaxExpansion) + " to 1)");
    std::vector<uint8_t> out(count * stride);
    const uint8_t* src = doc.buffers[buffer].data() + offset;
    int rc = -1;
    if (mode == "ATTRIBUTES") {
      if (stride % 4) fail(doc, where + ".byteStride must be a multiple of 4 in mode ATTRIBUTES");
      rc = meshopt_decodeVertexBuffer(out.data(), count, stride, src, length);
    } else if (mode == "TRIANGLES") {
      if ((stride != 2 && stride != 4) || count % 3) fail(doc, where + ": mode TRIANGLES needs byteStride 2 or 4 and count a multiple of 3");
      rc = meshopt_decodeIndexBuffer(out.data(), count, stride, src, length);
    } else if (mode == "INDICES") {
      if (stride != 2 && stride != 4) fail(doc, where + ": mode INDICES needs byteStride 2 or 4");
      rc = meshopt_decodeIndexSequence(out.data(), count, stride, src, length);
    } else {
      fail(doc, where + ".mode '" + mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    if (rc != 0) fail(doc, where + ": the compressed data does not decode (meshopt error " + std::to_string(rc) + ")");
    if (filter == "OCTAHEDRAL")
      meshopt_decodeFilterOct(out.data(), count, stride);
    else if (filter == "QUATERNION")
      meshopt_decodeFilterQuat(out.data(), count, stride);
    else if (filter == "EXPONENTIAL")
      meshopt_decodeFilterExp(out.data(), count, stride);
    else if (filter != "NONE")
      fail(doc, where + ".filter '" + filter + "' is unknown");
    if (out.size() != view.value("byteLength", size_t{0}))
      fail(doc, where + ": count x byteStride = " + std::to_string(out.size()) + " differs from the bufferView's byteLength");
    // The decoded bytes become the bufferView's own data.
    nlohmann::json& buffers = doc.json["buffers"];
    buffers.push_back({{"byteLength", out.size()}});
    doc.buffers.push_back(std::move(out));
    view["buffer"] = buffers.size() - 1;
    view.erase("byteOffset");
    view["extensions"].erase(kMeshopt);
    if (view["extensions"].empty()) view.erase("extensions");
    ++decoded;
  }
  if (decoded) remove_extension_declaration(doc, kMeshopt);
  // Its fallback buffers (no data of their own) are no longer needed: compact() drops what no bufferView uses.
  return decoded;
}

}  // namespace prm::gltf
