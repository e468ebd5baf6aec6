// rksolve's progress line: the time left from the last interval's pace (in forming the step keeps
// shrinking, and the run's average pace promises too little), and the first die's stroke and force.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "io/progress.hpp"

namespace {

// Everything a Progress wrote into a temporary file.
std::string written(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  char buf[512];
  while (std::fgets(buf, sizeof buf, f)) text += buf;
  return text;
}

const std::vector<std::string> kColumns = {"time", "kinetic", "die.stroke", "die.force"};

TEST(Progress, TimeLeftFromTheLastIntervalsPace) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  rk::State st;
  rk::Progress progress(true, 2, 100.0, 10.0, 0.0, 1e-3, kColumns, "die", st, f);
  const std::vector<double> row = {0, 0, 1.25e-3, 35e3};
  // the pace halves: 0.2 ms in the first 10 s, 0.1 ms in the next 10 s; 0.7 ms are left
  st.t = 0.2e-3, st.step = 1000;
  progress.step(st, 1e-9, 1e-4, row, 109.0);  // within the interval: nothing printed
  EXPECT_EQ(written(f), "");
  progress.step(st, 1e-9, 1e-4, row, 110.5);
  st.t = 0.3e-3, st.step = 3000;
  progress.step(st, 1e-9, 1e-4, row, 121.0);
  const std::string text = written(f);
  // 0.7 ms at the last 10.5 s's 0.1 ms: 73.5 s; the run's average pace (0.3 ms in 21 s) would say 49 s
  EXPECT_NE(text.find("ETA 74 s"), std::string::npos) << text;
  EXPECT_NE(text.find("step 3000  190 steps/s"), std::string::npos) << text;  // 2000 steps in 10.5 s
  // the stroke in mm and the force in kN, from the history row
  EXPECT_NE(text.find("die.stroke 1.25 mm, 35 kN"), std::string::npos) << text;
  EXPECT_NE(text.find("t = 0.0003 s ( 30.0 %)"), std::string::npos) << text;
  std::fclose(f);
}

TEST(Progress, AStageCountsFromItsStart) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  rk::State st;
  st.t = 1.0;  // a stage from 1 s to 3 s on the chain's clock
  rk::Progress progress(true, 1, 0.0, 1.0, 1.0, 3.0, {"time"}, "", st, f);
  st.t = 1.5;
  progress.step(st, 1e-3, 0, {0}, 2.0);
  const std::string text = written(f);
  EXPECT_NE(text.find("t = 1.5 s ( 25.0 %)"), std::string::npos) << text;
  EXPECT_NE(text.find("ETA 6 s"), std::string::npos) << text;  // 1.5 s left at 0.5 s per 2 s
  std::fclose(f);
}

TEST(Progress, NoDieNoStrokeAndQuietPrintsNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  rk::State st;
  rk::Progress plain(true, 1, 0.0, 1.0, 0.0, 1.0, {"time"}, "", st, f);
  st.t = 0.5, st.step = 10;
  plain.step(st, 1e-3, 0, {0}, 2.0);
  const std::string text = written(f);
  EXPECT_NE(text.find("ETA 2 s"), std::string::npos) << text;
  EXPECT_EQ(text.find("mm"), std::string::npos) << text;
  // the banner names multi-rate steps where the run takes them (time.subcycling auto resolves per scene)
  std::FILE* g = std::tmpfile();
  ASSERT_NE(g, nullptr);
  rk::Progress(true, 2, 0.0, 1.0, 0.0, 1.0, {"time"}, "", st, g).banner(false, 0.1, 1, 16);
  rk::Progress(true, 2, 0.0, 1.0, 0.0, 1.0, {"time"}, "", st, g).banner(false, 0.1, 1, 1);
  const std::string banners = written(g);
  EXPECT_NE(banners.find("mass scaling 1, multi-rate steps up to 16x, running to t = 1 s\nrksolve: 2 ranks, setup 0.10 s, "
                         "mass scaling 1, running to"),
            std::string::npos) << banners;
  std::fclose(g);
  rk::Progress quiet(false, 1, 0.0, 1.0, 0.0, 1.0, {"time"}, "", st, f);
  quiet.banner(false, 0.1, 1, 16);
  st.t = 0.7;
  quiet.step(st, 1e-3, 0, {0}, 5.0);
  quiet.done(10, 5.0, 100, 700, 0);
  EXPECT_EQ(written(f), text);
  std::fclose(f);
}

}  // namespace
