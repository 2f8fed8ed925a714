#include "prm/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <vector>

namespace prm {
namespace {

using Clock = std::chrono::steady_clock;

// Nothing is shown during a job's (or an unplanned Progress's) first second: short work shows nothing.
constexpr auto kTerminalQuiet = std::chrono::seconds(1);
constexpr auto kTerminalInterval = std::chrono::milliseconds(200);  // between redraws of the terminal line
constexpr auto kJsonInterval = std::chrono::milliseconds(500);      // between JSON lines of a running Progress
constexpr double kMaxAttemptShare = 0.95;  // of an attempt its rounds may claim (they are an estimate)
constexpr const char* kEraseLine = "\r\x1b[K";
constexpr size_t kDefaultColumns = 80;

std::string thousands(long long n) {
  std::string digits = std::to_string(n < 0 ? -n : n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return n < 0 ? "-" + out : out;
}

std::string duration_text(double s) {
  char buf[48];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.0f s", std::ceil(s));
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  else std::snprintf(buf, sizeof buf, "%d h %02d min", static_cast<int>(s) / 3600, static_cast<int>(s) / 60 % 60);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string json_number(double v) {
  if (v < 0 || !std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

size_t terminal_columns() {
  winsize w{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  if (const char* c = std::getenv("COLUMNS")) {
    const long n = std::strtol(c, nullptr, 10);
    if (n > 0) return static_cast<size_t>(n);
  }
  return kDefaultColumns;
}

// The one line's state, shared by the job and every Progress.
struct LineState {
  std::mutex mutex;
  bool mode_known = false;
  ProgressMode mode = ProgressMode::off;
  int schema = 1;
  // The job.
  bool job = false;
  Clock::time_point job_start;
  std::string stage;
  int attempt = 0, attempts_planned = 0, rounds_per_attempt = 0, rounds_in_attempt = 0;
  int rounds_this_attempt = 0;  // rounds_per_attempt, or what rounds_left() said
  long long best_bytes = -1;
  // The running Progress objects, innermost last.
  std::vector<const Progress*> running;
  std::vector<std::string> labels;
  std::vector<Clock::time_point> starts;
  std::vector<double> fractions;  // of each running Progress, 0..1
  // What was drawn.
  bool drawn = false;
  Clock::time_point last_emit;
};

LineState& state() {
  static LineState s;
  return s;
}

ProgressMode mode_locked(LineState& s) {
  if (!s.mode_known) {
    s.mode = isatty(STDERR_FILENO) ? ProgressMode::terminal : ProgressMode::off;
    s.mode_known = true;
  }
  return s.mode;
}

ProgressStatus status_locked(const LineState& s, Clock::time_point now) {
  ProgressStatus st;
  const std::string label = s.labels.empty() ? std::string() : s.labels.back();
  const Clock::time_point start = s.job ? s.job_start : (s.starts.empty() ? now : s.starts.front());
  st.elapsed_seconds = std::chrono::duration<double>(now - start).count();
  st.fraction = s.fractions.empty() ? -1 : s.fractions.back();
  if (s.job) {
    st.stage = s.stage;
    st.detail = label;
    st.attempt = s.attempt;
    st.attempts_planned = s.attempts_planned;
    st.best_bytes = s.best_bytes;
    if (s.attempts_planned > 0 && s.attempt > 0 && s.rounds_per_attempt > 0) {
      const double within =
          std::min(kMaxAttemptShare, static_cast<double>(s.rounds_in_attempt) / std::max(1, s.rounds_this_attempt));
      st.eta_seconds = estimate_seconds_left(st.elapsed_seconds, s.attempt - 1 + within, s.attempts_planned);
    }
  } else if (!s.fractions.empty()) {
    // The time left of the outermost task (it holds the others), or of the innermost before the outermost moved.
    st.stage = label;
    const size_t i = s.fractions.front() > 0 ? 0 : s.fractions.size() - 1;
    if (s.fractions[i] > 0)
      st.eta_seconds =
          estimate_seconds_left(std::chrono::duration<double>(now - s.starts[i]).count(), s.fractions[i], 1.0);
  }
  return st;
}

// Draws or writes the line when due (`force`: a change of stage, attempt or best stream).
void emit_locked(LineState& s, bool force) {
  const ProgressMode mode = mode_locked(s);
  if (mode == ProgressMode::off) return;
  if (!s.job && s.labels.empty()) return;
  const Clock::time_point now = Clock::now();
  if (mode == ProgressMode::terminal) {
    const Clock::time_point start = s.job ? s.job_start : s.starts.front();
    if (now - start < kTerminalQuiet) return;
    if (!force && s.drawn && now - s.last_emit < kTerminalInterval) return;
    const std::string line = format_progress_line(status_locked(s, now), terminal_columns());
    std::fprintf(stderr, "%s%s", kEraseLine, line.c_str());
    s.drawn = true;
  } else {
    if (!force && now - s.last_emit < kJsonInterval) return;
    std::fprintf(stderr, "%s\n", format_progress_json(status_locked(s, now), s.schema).c_str());
  }
  std::fflush(stderr);
  s.last_emit = now;
}

void clear_locked(LineState& s) {
  if (!s.drawn) return;
  std::fputs(kEraseLine, stderr);
  std::fflush(stderr);
  s.drawn = false;
}

}  // namespace

std::string format_progress_line(const ProgressStatus& s, size_t columns) {
  if (columns <= 1) return {};
  const size_t width = columns - 1;
  std::string head = s.stage;
  // "remesh: resampling reliefs" inside the stage "remesh" is shown once.
  if (!s.detail.empty())
    head = head.empty() || s.detail.rfind(head + ": ", 0) == 0 ? s.detail : head + ": " + s.detail;
  std::string tail;
  auto add = [&](const std::string& part) { tail += "  " + part; };
  if (s.attempt > 0)
    add("attempt " + std::to_string(s.attempt) +
        (s.attempts_planned > 0 ? " of " + std::to_string(std::max(s.attempts_planned, s.attempt)) : ""));
  if (s.best_bytes >= 0) add("best " + thousands(s.best_bytes) + " B");
  if (s.fraction >= 0) add(std::to_string(static_cast<int>(100 * std::min(1.0, s.fraction))) + "%");
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f s", s.elapsed_seconds);
  add(buf);
  if (s.eta_seconds >= 0) add("~" + duration_text(s.eta_seconds) + " left");
  // The numbers matter more than the full label: the label is shortened first ("..."), then the whole line cut.
  if (head.size() + tail.size() > width && tail.size() + 3 < width) head = head.substr(0, width - tail.size() - 3) + "...";
  std::string line = head + tail;
  if (line.size() > width) line.resize(width);
  return line;
}

std::string format_progress_json(const ProgressStatus& s, int schema) {
  std::string j = "{\"schema\":" + std::to_string(schema) + ",\"stage\":" + json_string(s.stage);
  j += ",\"detail\":" + json_string(s.detail);
  j += ",\"fraction\":" + json_number(s.fraction);
  j += ",\"attempt\":" + std::to_string(s.attempt);
  j += ",\"attempts_planned\":" + std::to_string(s.attempts_planned);
  j += ",\"best_bytes\":" + (s.best_bytes >= 0 ? std::to_string(s.best_bytes) : std::string("null"));
  j += ",\"elapsed_seconds\":" + json_number(s.elapsed_seconds);
  j += ",\"eta_seconds\":" + json_number(s.eta_seconds) + "}";
  return j;
}

double estimate_seconds_left(double elapsed, double done, double planned) {
  if (done <= 0 || elapsed < 0) return -1;
  return std::max(0.0, elapsed * (planned - done) / done);
}

// ---- Progress ----

void Progress::set_mode(ProgressMode mode, int schema) {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (mode != ProgressMode::terminal) clear_locked(s);
  s.mode = mode;
  s.schema = schema;
  s.mode_known = true;
}

ProgressMode Progress::mode() {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  return mode_locked(s);
}

void Progress::set_enabled(bool enabled) {
  if (!enabled) return set_mode(ProgressMode::off);
  set_mode(isatty(STDERR_FILENO) ? ProgressMode::terminal : ProgressMode::off);
}

bool Progress::enabled() { return mode() != ProgressMode::off; }

void Progress::clear() {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  clear_locked(s);
}

Progress::Progress(std::string label, size_t total)
    : label_(std::move(label)), total_(total ? total : 1), start_(Clock::now()) {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  s.running.push_back(this);
  s.labels.push_back(label_);
  s.starts.push_back(start_);
  s.fractions.push_back(0);
  emit_locked(s, s.job);  // a job's line shows the new detail at once
}

Progress::~Progress() { finish(); }

void Progress::advance(size_t units) {
  done_ += units;
  update(false);
}

void Progress::set(size_t done) {
  done_ = done;
  update(false);
}

void Progress::update(bool force) {
  LineState& s = state();
  std::unique_lock<std::mutex> lock(s.mutex, std::try_to_lock);  // workers never wait for the line
  if (!lock.owns_lock()) return;
  const auto it = std::find(s.running.begin(), s.running.end(), this);
  if (it == s.running.end()) return;
  s.fractions[static_cast<size_t>(it - s.running.begin())] =
      static_cast<double>(std::min<size_t>(done_, total_)) / static_cast<double>(total_);
  emit_locked(s, force);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  const auto it = std::find(s.running.begin(), s.running.end(), this);
  if (it == s.running.end()) return;
  const size_t i = static_cast<size_t>(it - s.running.begin());
  s.running.erase(it);
  s.labels.erase(s.labels.begin() + static_cast<std::ptrdiff_t>(i));
  s.starts.erase(s.starts.begin() + static_cast<std::ptrdiff_t>(i));
  s.fractions.erase(s.fractions.begin() + static_cast<std::ptrdiff_t>(i));
  if (!s.job && s.running.empty()) clear_locked(s);
}

// ---- ProgressJob ----

ProgressJob::ProgressJob(int attempts_planned, int rounds_per_attempt) {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  owner_ = !s.job;
  if (!owner_) return;
  s.job = true;
  s.job_start = Clock::now();
  s.stage.clear();
  s.attempt = s.rounds_in_attempt = 0;
  s.attempts_planned = std::max(0, attempts_planned);
  s.rounds_per_attempt = std::max(0, rounds_per_attempt);
  s.best_bytes = -1;
}

ProgressJob::~ProgressJob() {
  if (!owner_) return;
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  s.stage = "done";
  s.labels.clear();
  s.running.clear();
  s.starts.clear();
  s.fractions.clear();
  if (mode_locked(s) == ProgressMode::json) {
    ProgressStatus st = status_locked(s, Clock::now());
    st.eta_seconds = 0;
    std::fprintf(stderr, "%s\n", format_progress_json(st, s.schema).c_str());
    std::fflush(stderr);
  }
  clear_locked(s);
  s.job = false;
}

void ProgressJob::stage(const std::string& name) {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.job || s.stage == name) return;
  s.stage = name;
  emit_locked(s, true);
}

void ProgressJob::attempt(int k) {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.job) return;
  s.attempt = k;
  s.rounds_in_attempt = 0;
  s.rounds_this_attempt = s.rounds_per_attempt;
  if (s.attempts_planned > 0 && k > s.attempts_planned) s.attempts_planned = k;
  emit_locked(s, true);
}

void ProgressJob::best_bytes(size_t bytes) {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.job) return;
  s.best_bytes = static_cast<long long>(bytes);
  emit_locked(s, true);
}

void ProgressJob::advance_round() {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.job) return;
  ++s.rounds_in_attempt;
  s.rounds_this_attempt = std::max(s.rounds_this_attempt, s.rounds_in_attempt + 1);
  emit_locked(s, false);
}

void ProgressJob::rounds_left(int n) {
  LineState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.job) return;
  s.rounds_this_attempt = s.rounds_in_attempt + std::max(0, n);
}

}  // namespace prm
