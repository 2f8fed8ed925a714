// The one translation unit that compiles tinygltf (Debian's libtinygltf-dev header, MIT). Its namespace is renamed
// to prm_tinygltf by a compile definition on the prm_tinygltf target, so that it cannot clash with the older copy of
// tinygltf that libdraco exports (docs: ../shared/guide/ECOSYSTEM.md §2.3). Images are not decoded.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
