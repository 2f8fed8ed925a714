// §4.5 A per-corner table that holds only the corners decoded so far. Spirale Reversi (§6.4) decodes the triangles
// from the last forward index down to 0, so the table holds the corners [first(), size) and grows towards 0, by
// doubling, as triangles arrive: its memory follows what is decoded, never the count the stream claims.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace prm::codec {

template <typename T>
class TailTable {
 public:
  // An empty table of `size` entries, none held yet; entries made available later start as `fill`.
  void reset(size_t size, T fill) {
    size_ = size;
    fill_ = fill;
    data_.clear();
    first_ = size;
  }
  // Room ahead for the entries [size - count, size) (a caller that trusts its size).
  void reserve_tail(size_t count) { grow(std::min(count, size_)); }
  // Makes the entries [c, size) available.
  void extend_to(size_t c) {
    if (c < first_) grow(std::max({size_ - c, 2 * (size_ - first_), kMinHeld}));
  }
  size_t first() const { return first_; }
  T& operator[](size_t c) { return data_[c - first_]; }
  const T& operator[](size_t c) const { return data_[c - first_]; }
  // The whole table, once first() is 0.
  std::vector<T>& all() { return data_; }
  const std::vector<T>& all() const { return data_; }

 private:
  // The first growth holds min(size, kMinHeld) entries: a constant (§4.5 allows one per stream, 192 kB for a table
  // of 4-byte entries), so meshes of up to 16,384 triangles decode without a copy, larger ones with fewer.
  static constexpr size_t kMinHeld = 3 * 16384;
#if defined(__GNUC__) || defined(__clang__)
  __attribute__((noinline))
#endif
  void grow(size_t held) {
    held = std::min(held, size_);
    const size_t have = size_ - first_;
    if (held <= have) return;
    std::vector<T> grown;
    grown.reserve(held);
    grown.assign(held - have, fill_);
    grown.insert(grown.end(), data_.begin(), data_.end());
    data_.swap(grown);
    first_ = size_ - held;
  }

  std::vector<T> data_;
  size_t size_ = 0, first_ = 0;
  T fill_{};
};

}  // namespace prm::codec
