// The progress line's text (width clipping, the estimate of the time left) and its JSON lines.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "prm/progress.h"

namespace prm {
namespace {

ProgressStatus pack_status() {
  ProgressStatus s;
  s.stage = "remesh";
  s.detail = "remesh: resampling reliefs";
  s.fraction = 0.42;
  s.attempt = 2;
  s.attempts_planned = 3;
  s.best_bytes = 5391;
  s.elapsed_seconds = 12.34;
  s.eta_seconds = 8.2;
  return s;
}

TEST(ProgressLine, ShowsStageAttemptBestShareTimeAndEstimate) {
  EXPECT_EQ(format_progress_line(pack_status(), 200),
            "remesh: resampling reliefs  attempt 2 of 3  best 5,391 B  42%  12.3 s  ~9 s left");
  ProgressStatus other = pack_status();
  other.detail = "resampling";
  EXPECT_EQ(format_progress_line(other, 200).rfind("remesh: resampling  attempt 2 of 3", 0), 0u);
}

TEST(ProgressLine, UnknownFieldsAreLeftOut) {
  ProgressStatus s;
  s.stage = "compare";
  s.elapsed_seconds = 1.0;
  EXPECT_EQ(format_progress_line(s, 80), "compare  1.0 s");
}

TEST(ProgressLine, NeverReachesTheLastColumn) {
  const ProgressStatus s = pack_status();
  const std::string full = format_progress_line(s, 1000);
  for (size_t columns : {2, 10, 30, 60, 79, 80, 81, 120}) {
    const std::string line = format_progress_line(s, columns);
    EXPECT_LE(line.size(), columns - 1) << columns;
    EXPECT_EQ(line.find('\n'), std::string::npos);
    if (full.size() <= columns - 1) {
      EXPECT_EQ(line, full);
    }
  }
  EXPECT_EQ(format_progress_line(s, 1), "");
  EXPECT_EQ(format_progress_line(s, 0), "");
}

TEST(ProgressLine, ClipsTheLabelBeforeTheNumbers) {
  const std::string line = format_progress_line(pack_status(), 70);
  EXPECT_EQ(line.size(), 69u);
  // The numbers stay whole; the label is shortened with "...".
  EXPECT_NE(line.find("~9 s left"), std::string::npos) << line;
  EXPECT_NE(line.find("...  attempt 2 of 3"), std::string::npos) << line;
}

TEST(ProgressLine, LongEstimatesInMinutesAndHours) {
  ProgressStatus s;
  s.stage = "remesh";
  s.eta_seconds = 125;
  EXPECT_NE(format_progress_line(s, 80).find("~2 min 05 s left"), std::string::npos);
  s.eta_seconds = 7300;
  EXPECT_NE(format_progress_line(s, 80).find("~2 h 01 min left"), std::string::npos);
}

TEST(ProgressEstimate, LinearInTheShareDone) {
  EXPECT_DOUBLE_EQ(estimate_seconds_left(10, 1, 4), 30);
  EXPECT_DOUBLE_EQ(estimate_seconds_left(10, 2.5, 5), 10);
  EXPECT_DOUBLE_EQ(estimate_seconds_left(10, 5, 4), 0);  // more done than planned: nothing left, never negative
  EXPECT_LT(estimate_seconds_left(10, 0, 4), 0);          // nothing done: unknown
}

TEST(ProgressJson, OneObjectWithTheSchemaAndEveryField) {
  ProgressStatus s = pack_status();
  s.detail = "a \"quoted\" label\\";
  const std::string line = format_progress_json(s, 7);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(line);
  EXPECT_EQ(j["schema"], 7);
  EXPECT_EQ(j["stage"], "remesh");
  EXPECT_EQ(j["detail"], s.detail);
  EXPECT_EQ(j["attempt"], 2);
  EXPECT_EQ(j["attempts_planned"], 3);
  EXPECT_EQ(j["best_bytes"], 5391);
  EXPECT_NEAR(j["elapsed_seconds"].get<double>(), 12.34, 1e-9);
  EXPECT_NEAR(j["eta_seconds"].get<double>(), 8.2, 1e-9);
  EXPECT_NEAR(j["fraction"].get<double>(), 0.42, 1e-9);
  s.best_bytes = -1;
  s.eta_seconds = -1;
  const nlohmann::json unknown = nlohmann::json::parse(format_progress_json(s, 1));
  EXPECT_TRUE(unknown["best_bytes"].is_null());
  EXPECT_TRUE(unknown["eta_seconds"].is_null());
}

}  // namespace
}  // namespace prm
