// A bounds-checked tokenizer over a file held in memory, for the ASCII formats. Every failure names the file
// and the line.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "mesh_io_internal.h"

namespace prm::io {

class TextScanner {
 public:
  TextScanner(const char* begin, const char* end, std::string path, char comment = '\0')
      : p_(begin), end_(end), path_(std::move(path)), comment_(comment) {}

  // Comments skipped from now on are appended here (without the comment character and one blank after it).
  void collect_comments(std::vector<std::string>* out) { comments_ = out; }
  // The line number of the first byte (when the scanner starts after a header read elsewhere).
  void set_line(size_t line) { line_ = line; }
  // What an unexpected end of file probably means, for the message.
  void set_eof_hint(std::string hint) { eof_hint_ = std::move(hint); }

  // Skips blanks, line breaks and comments (from the comment character to the end of the line).
  void skip_space() {
    while (p_ < end_) {
      const char c = *p_;
      if (c == '\n') {
        ++line_;
        ++p_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++p_;
      } else if (comment_ && c == comment_) {
        const char* s = ++p_;
        while (p_ < end_ && *p_ != '\n') ++p_;
        if (comments_) {
          const char* e = p_;
          if (e > s && e[-1] == '\r') --e;
          if (s < e && *s == ' ') ++s;
          comments_->emplace_back(s, e);
        }
      } else {
        break;
      }
    }
  }
  // Skips blanks on the current line only.
  void skip_blanks() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r')) ++p_;
  }
  bool at_end() {
    skip_space();
    return p_ >= end_;
  }
  // True when only blanks (or a comment) remain on the current line.
  bool at_line_end() {
    skip_blanks();
    return p_ >= end_ || *p_ == '\n' || (comment_ && *p_ == comment_);
  }
  void skip_line() {
    while (p_ < end_ && *p_ != '\n') ++p_;
    if (p_ < end_) {
      ++p_;
      ++line_;
    }
  }
  std::string_view token(const char* what) {
    skip_space();
    if (p_ >= end_)
      fail("unexpected end of file while reading " + std::string(what) + " (" + eof_hint_ + ")");
    const char* s = p_;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    return {s, static_cast<size_t>(p_ - s)};
  }
  // A token on the current line (fails at the end of the line).
  std::string_view line_token(const char* what) {
    if (at_line_end()) fail("line ends before " + std::string(what));
    return token(what);
  }
  double number(const char* what) { return parse_double(token(what), what); }
  int64_t integer(const char* what) { return parse_int(token(what), what); }

  double parse_double(std::string_view t, const char* what) {
    double v = 0;
    const char* b = t.data();
    if (!t.empty() && *b == '+') ++b;  // from_chars does not take a leading '+'
    const auto r = std::from_chars(b, t.data() + t.size(), v);
    // "nan" and "inf" parse; check_finite() rejects them with the vertex named.
    if (r.ec == std::errc::result_out_of_range && r.ptr == t.data() + t.size()) {
      // from_chars leaves v unset on overflow and on underflow: underflow is a zero, overflow an error.
      const std::string s(t);
      const double x = std::strtod(s.c_str(), nullptr);
      if (std::isfinite(x)) return x;
      fail("'" + std::string(t.substr(0, 40)) + "' does not fit a double (" + what + ")");
    }
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail("'" + std::string(t.substr(0, 40)) + "' is not a number (" + what + ")");
    return v;
  }
  int64_t parse_int(std::string_view t, const char* what) {
    int64_t v = 0;
    const char* b = t.data();
    if (!t.empty() && *b == '+') ++b;
    const auto r = std::from_chars(b, t.data() + t.size(), v);
    if (r.ec == std::errc::result_out_of_range)
      fail("'" + std::string(t.substr(0, 40)) + "' is too large (" + what + ")");
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail("'" + std::string(t.substr(0, 40)) + "' is not an integer (" + what + ")");
    return v;
  }

  [[noreturn]] void fail(const std::string& what) const {
    io::fail(path_, "line " + std::to_string(line_) + ": " + what);
  }
  size_t line() const { return line_; }
  size_t remaining() const { return static_cast<size_t>(end_ - p_); }
  const char* position() const { return p_; }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  }
  const char* p_;
  const char* end_;
  std::string path_;
  char comment_;
  std::vector<std::string>* comments_ = nullptr;
  std::string eof_hint_ = "truncated file";
  size_t line_ = 1;
};

}  // namespace prm::io
