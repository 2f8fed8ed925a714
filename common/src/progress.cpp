#include "prm/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace prm {
namespace {
std::atomic<bool> g_enabled{true};
}

void Progress::set_enabled(bool enabled) { g_enabled = enabled; }
bool Progress::enabled() { return g_enabled; }

Progress::Progress(std::string label, size_t total)
    : label_(std::move(label)), total_(total ? total : 1), active_(g_enabled && isatty(STDERR_FILENO)) {
  start_ = last_draw_ = std::chrono::steady_clock::now();
}

Progress::~Progress() { finish(); }

void Progress::advance(size_t units) {
  done_ += units;
  draw(false);
}

void Progress::set(size_t done) {
  done_ = done;
  draw(false);
}

void Progress::draw(bool force) {
  if (!active_) return;
  std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  const auto now = std::chrono::steady_clock::now();
  // Stay silent during the first second: short work shows nothing.
  if (!force && now - start_ < std::chrono::seconds(1)) return;
  const size_t done = std::min<size_t>(done_, total_);
  const int percent = static_cast<int>(100.0 * static_cast<double>(done) / static_cast<double>(total_));
  if (!force && percent == last_percent_ && now - last_draw_ < std::chrono::milliseconds(250)) return;
  last_percent_ = percent;
  last_draw_ = now;
  const int width = 30, filled = percent * width / 100;
  std::string bar(static_cast<size_t>(filled), '#');
  bar.append(static_cast<size_t>(width - filled), ' ');
  const double secs = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r%s [%s] %3d%%  %.1fs", label_.c_str(), bar.c_str(), percent, secs);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (!active_) return;
  if (drawn_) {
    done_ = total_;
    draw(true);
    std::fputc('\n', stderr);
  }
  active_ = false;
}

}  // namespace prm
