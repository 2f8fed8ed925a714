// hdecode8's faster entropy layer, the coder: static per-stream frequency tables (one per context, 2^11 total),
// two interleaved rANS states (32 bits, 16-bit words; symbol i uses state i & 1) and a separate stream of raw bits.
// Not a format: a bench prototype whose table bytes are counted with a plain serialization (varints).
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

namespace entropy_study {

constexpr uint32_t kRansBits = 11;
constexpr uint32_t kRansOne = 1u << kRansBits;
constexpr uint32_t kRansLow = 1u << 16;  // the state lives in [2^16, 2^32)

inline void put_varint(std::vector<uint8_t>& out, uint64_t v) {
  for (; v >= 0x80; v >>= 7) out.push_back(static_cast<uint8_t>(v | 0x80));
  out.push_back(static_cast<uint8_t>(v));
}

// The tables of one kind of value: per context id (sparse), `alphabet` symbols.
class StaticTables {
 public:
  explicit StaticTables(uint32_t alphabet) : alphabet_(alphabet) {}
  void count(uint32_t ctx, uint32_t symbol) {
    auto& c = counts_[ctx];
    if (c.empty()) c.assign(alphabet_, 0);
    ++c[symbol];
  }
  // Normalizes the counts (every seen symbol keeps a frequency >= 1) and builds the decoding tables.
  void build() {
    dense_.clear();
    for (const auto& [ctx, c] : counts_) {
      if (ctx >= dense_.size()) dense_.resize(ctx + 1, 0);
      dense_[ctx] = static_cast<uint32_t>(freq_.size() / alphabet_);
      std::vector<uint32_t> f = normalize(c);
      uint32_t cum = 0;
      for (uint32_t s = 0; s < alphabet_; ++s) {
        freq_.push_back(f[s] | cum << 16);
        for (uint32_t k = 0; k < f[s]; ++k) slot_.push_back(static_cast<uint8_t>(s));
        cum += f[s];
      }
    }
  }
  // The table header a stream would carry: context count, then per context the gap to the previous id, the
  // alphabet's used length and each frequency (varints).
  size_t header_bytes() const {
    std::vector<uint8_t> out;
    put_varint(out, counts_.size());
    uint32_t prev = 0;
    for (const auto& [ctx, c] : counts_) {
      put_varint(out, ctx - prev);
      prev = ctx;
      const uint32_t d = dense_[ctx];
      uint32_t used = alphabet_;
      while (used > 0 && (freq_[d * alphabet_ + used - 1] & 0xFFFF) == 0) --used;
      put_varint(out, used);
      for (uint32_t s = 0; s < used; ++s) put_varint(out, freq_[d * alphabet_ + s] & 0xFFFF);
    }
    return out.size();
  }
  size_t contexts() const { return counts_.size(); }
  uint32_t dense(uint32_t ctx) const { return dense_[ctx]; }
  // freq | cum << 16 of `symbol` in dense context d; the symbol of slot `slot`.
  uint32_t freq_cum(uint32_t d, uint32_t symbol) const { return freq_[d * alphabet_ + symbol]; }
  const uint32_t* freq_table(uint32_t d) const { return freq_.data() + size_t{d} * alphabet_; }
  const uint8_t* slot_table(uint32_t d) const { return slot_.data() + size_t{d} * kRansOne; }

 private:
  std::vector<uint32_t> normalize(const std::vector<uint64_t>& c) const {
    uint64_t total = 0;
    for (uint64_t x : c) total += x;
    std::vector<uint32_t> f(alphabet_, 0);
    int64_t sum = 0;
    for (uint32_t s = 0; s < alphabet_; ++s) {
      if (c[s] == 0) continue;
      f[s] = static_cast<uint32_t>(std::max<uint64_t>(1, (c[s] * kRansOne + total / 2) / total));
      sum += f[s];
    }
    while (sum != kRansOne) {  // the largest frequency absorbs the rounding
      const uint32_t s = static_cast<uint32_t>(std::max_element(f.begin(), f.end()) - f.begin());
      if (sum > kRansOne) {
        const int64_t d = std::min<int64_t>(sum - kRansOne, int64_t{f[s]} - 1);
        f[s] -= static_cast<uint32_t>(d);
        sum -= d;
        if (d == 0) break;  // cannot happen with fewer than 2^11 symbols
      } else {
        f[s] += static_cast<uint32_t>(kRansOne - sum);
        sum = kRansOne;
      }
    }
    return f;
  }
  uint32_t alphabet_;
  std::map<uint32_t, std::vector<uint64_t>> counts_;
  std::vector<uint32_t> dense_;
  std::vector<uint32_t> freq_;  // dense context * alphabet: freq | cum << 16
  std::vector<uint8_t> slot_;   // dense context * 2^11: the symbol
};

// rANS encoding runs backwards: symbols are queued forwards (freq | cum << 16) and coded in reverse at finish().
class RansEncoder {
 public:
  void queue(uint32_t freq_cum) { queued_.push_back(freq_cum); }
  std::vector<uint16_t> finish() {
    uint32_t x[2] = {kRansLow, kRansLow};
    std::vector<uint16_t> words;
    for (size_t i = queued_.size(); i-- > 0;) {
      uint32_t& s = x[i & 1];
      const uint32_t freq = queued_[i] & 0xFFFF, cum = queued_[i] >> 16;
      if (s >= (uint64_t{freq} << (32 - kRansBits))) {  // 64 bits: freq may be 2^11
        words.push_back(static_cast<uint16_t>(s));
        s >>= 16;
      }
      s = ((s / freq) << kRansBits) + s % freq + cum;
    }
    for (int lane = 1; lane >= 0; --lane) {
      words.push_back(static_cast<uint16_t>(x[lane]));
      words.push_back(static_cast<uint16_t>(x[lane] >> 16));
    }
    std::reverse(words.begin(), words.end());
    return words;
  }

 private:
  std::vector<uint32_t> queued_;
};

class RansDecoder {
 public:
  RansDecoder() = default;
  RansDecoder(const uint16_t* words, size_t n) { reset(words, n); }
  void reset(const uint16_t* words, size_t n) {
    p_ = words;
    end_ = words + n;
    for (auto& s : x_) s = uint32_t{word()} << 16 | word();
  }
  // The next symbol, decoded on state `lane` with one context's tables.
  inline uint32_t get(uint32_t lane, const uint32_t* freq_cum, const uint8_t* slots) {
    uint32_t& s = x_[lane];
    const uint32_t slot = s & (kRansOne - 1);
    const uint32_t sym = slots[slot];
    const uint32_t fc = freq_cum[sym];
    s = (fc & 0xFFFF) * (s >> kRansBits) + slot - (fc >> 16);
    if (s < kRansLow) s = s << 16 | word();
    return sym;
  }
  // Every word read and both states back at their start: the stream was decoded as it was coded.
  bool finish() const { return p_ == end_ && x_[0] == kRansLow && x_[1] == kRansLow; }

 private:
  inline uint16_t word() { return p_ < end_ ? *p_++ : 0; }
  const uint16_t* p_ = nullptr;
  const uint16_t* end_ = nullptr;
  uint32_t x_[2] = {0, 0};
};

// Raw bits, most significant first.
class BitWriter {
 public:
  void put(uint64_t v, int count) {
    for (int i = count - 1; i >= 0; --i) {
      cur_ = static_cast<uint8_t>(cur_ << 1 | ((v >> i) & 1));
      if (++n_ == 8) bytes_.push_back(cur_), cur_ = 0, n_ = 0;
    }
  }
  std::vector<uint8_t> finish() {
    if (n_) bytes_.push_back(static_cast<uint8_t>(cur_ << (8 - n_)));
    return std::move(bytes_);
  }

 private:
  std::vector<uint8_t> bytes_;
  uint8_t cur_ = 0;
  int n_ = 0;
};

class BitReader {
 public:
  BitReader() = default;
  BitReader(const uint8_t* p, size_t n) { reset(p, n); }
  void reset(const uint8_t* p, size_t n) {
    p_ = p;
    end_ = p + n;
    buf_ = 0;
    n_ = 0;
  }
  // 1..32 bits.
  inline uint32_t get(int count) {
    if (n_ < count) refill();
    const uint32_t v = static_cast<uint32_t>(buf_ >> (64 - count));
    buf_ <<= count;
    n_ -= count;
    return v;
  }
  bool exhausted_exactly() const { return p_ == end_ && n_ < 8; }

 private:
  void refill() {
    while (n_ <= 56) {
      buf_ |= uint64_t{p_ < end_ ? *p_++ : uint8_t{0}} << (56 - n_);
      n_ += 8;
    }
  }
  const uint8_t* p_ = nullptr;
  const uint8_t* end_ = nullptr;
  uint64_t buf_ = 0;
  int n_ = 0;
};

// Magnitude tokens: m < 16 is its own token; above, the class e = floor(log2 m) and the bit below the leading one
// (token 16 + 2 (e - 4) + that bit), the e - 1 lower bits raw. m < 2^41: tokens < 90.
constexpr uint32_t kTokenAlphabet = 96;
inline uint32_t magnitude_token(uint64_t m, int& raw_bits) {
  if (m < 16) {
    raw_bits = 0;
    return static_cast<uint32_t>(m);
  }
  const int e = 63 - __builtin_clzll(m);
  raw_bits = e - 1;
  return 16 + 2 * static_cast<uint32_t>(e - 4) + static_cast<uint32_t>((m >> (e - 1)) & 1);
}
inline uint64_t token_magnitude(uint32_t token, BitReader& raw) {
  if (token < 16) return token;
  const int e = static_cast<int>((token - 16) / 2 + 4);
  uint64_t m = uint64_t{2 | ((token - 16) & 1)};
  int rest = e - 1;
  if (rest > 32) m = m << 32 | raw.get(32), rest -= 32;
  return m << rest | raw.get(rest);
}
inline void put_magnitude_raw(BitWriter& raw, uint64_t m, int raw_bits) {
  if (raw_bits > 0) raw.put(m & ((uint64_t{1} << raw_bits) - 1), raw_bits);
}

}  // namespace entropy_study
