// One progress line for work that takes longer than a second (issue 21 "What a user sees").
//
// A job (e.g. `prm pack`) may declare its plan (ProgressJob): the stage, the attempt k of the planned attempts, the
// best stream so far and an estimate of the time left from the rounds the plan expects. The work inside a stage
// (remesh: resampling reliefs, ...) reports through Progress objects, which are folded into that same line as the
// stage's detail and percentage: there is never more than one line.
//
// Output (ProgressMode): on a terminal, one line on stderr redrawn in place with "\r" and erase-line ("\x1b[K"), no
// other cursor movement, clipped to the terminal's columns; as JSON lines on stderr (one object per update, for tools
// that wrap `prm`); or nothing. The default is the terminal line when stderr is a terminal, nothing otherwise.
// advance() and set() may be called from several threads.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <string>

namespace prm {

enum class ProgressMode { off, terminal, json };

// What the line shows. Negative numbers are unknown and left out.
struct ProgressStatus {
  std::string stage;              // "remesh", or a Progress label when no job is running
  std::string detail;             // the running Progress's label inside a job's stage
  double fraction = -1;           // of the running Progress, 0..1
  int attempt = 0;                // 1-based; 0: no attempts in this job
  int attempts_planned = 0;
  long long best_bytes = -1;      // the smallest stream so far
  double elapsed_seconds = 0;
  double eta_seconds = -1;
};

// "stage: detail  attempt 2/3  best 5,391 B  42%  12.3 s  ~8 s left", clipped to `columns` - 1 characters (the last
// column stays empty so that no terminal wraps the line). columns <= 1: nothing.
std::string format_progress_line(const ProgressStatus& s, size_t columns);
// {"schema":N,"stage":...,"detail":...,"fraction":...,"attempt":...,"attempts_planned":...,"best_bytes":...,
//  "elapsed_seconds":...,"eta_seconds":...}: one line, without the newline. Unknown numbers are null.
std::string format_progress_json(const ProgressStatus& s, int schema);
// The time left when `done` of `planned` units took `elapsed` seconds (linear); -1 when nothing is done yet.
double estimate_seconds_left(double elapsed, double done, double planned);

// Nested work inside the current stage: a count of units.
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

  // The output of every progress line (ProgressMode); `schema` is the JSON lines' "schema" value.
  static void set_mode(ProgressMode mode, int schema = 1);
  static ProgressMode mode();
  // set_enabled(false): off; set_enabled(true): the default (terminal if stderr is one).
  static void set_enabled(bool enabled);
  static bool enabled();
  // Erase the terminal line (before other output on the terminal); the next update draws it again.
  static void clear();

 private:
  void update(bool force);
  std::string label_;
  size_t total_;
  std::atomic<size_t> done_{0};
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

// A job with a plan: at most one at a time (the outermost one counts; nested ones are ignored). Its destructor
// ends the job: a final {"stage":"done"} JSON line, or the terminal line erased.
class ProgressJob {
 public:
  // attempts_planned: how many attempts the plan expects (0: none); rounds_per_attempt: the rounds (advance_round())
  // one attempt is expected to take, for the estimate of the time left.
  ProgressJob(int attempts_planned, int rounds_per_attempt);
  ~ProgressJob();
  ProgressJob(const ProgressJob&) = delete;
  ProgressJob& operator=(const ProgressJob&) = delete;

  static void stage(const std::string& name);
  static void attempt(int k);  // 1-based; raises attempts_planned when k exceeds it
  static void best_bytes(size_t bytes);
  static void advance_round();  // one planned round of the current attempt done
  static void rounds_left(int n);  // the current attempt is now expected to end after n more rounds

 private:
  bool owner_;
};

}  // namespace prm
