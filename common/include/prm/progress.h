// A progress line on the terminal for work that takes longer than a second.
// Writes "\r<label> [#####     ]  42%" to stderr, only when stderr is a terminal and progress is enabled.
// advance() and set() may be called from several threads.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace prm {

class Progress {
 public:
  // total: number of work units; label: what is being done ("remesh: resampling reliefs").
  Progress(std::string label, size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(size_t units = 1);
  void set(size_t done);
  void finish();

  // Globally disable (e.g. --quiet or --json) or enable progress output.
  static void set_enabled(bool enabled);
  static bool enabled();

 private:
  void draw(bool force);
  std::string label_;
  size_t total_;
  std::atomic<size_t> done_{0};
  std::mutex draw_mutex_;
  bool active_;
  bool drawn_ = false;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace prm
