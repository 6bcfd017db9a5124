#include "csv_record.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

using tycore::CsvRecord;

namespace {

std::string temp_path(const char* name)
{
  return ::testing::TempDir() + name + std::to_string(::getpid()) + ".csv";
}

std::string slurp(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}

}    // namespace

TEST(CsvRecord, NewRecordHasHeaderAndRows)
{
  const std::string path = temp_path("new");
  spit(path, "left over from another test\n");
  {
    CsvRecord r;
    r.start(path, "step,a,b");
    r.write_row(0, {1.5, -2.0});
    r.write_row(10, {0.1, 1e-300});
    EXPECT_EQ(r.last_step(), 10);
  }
  EXPECT_EQ(slurp(path), "step,a,b\n0,1.5,-2\n10,0.1,1e-300\n");
  std::remove(path.c_str());
}

// a run that crashed at step 35 after its restart file of step 20: the resumed run continues
// from step 20, so rows 30 and a torn row are superseded; steps never repeat or go back
TEST(CsvRecord, ResumeDropsRowsAfterTheResumedStepAndATornLine)
{
  const std::string path = temp_path("resume");
  spit(path, "step,a\n0,1\n10,2\n20,3\n30,4\n40,");
  CsvRecord r;
  r.resume(path, "step,a", 20);
  EXPECT_EQ(r.last_step(), 20);
  EXPECT_EQ(r.dropped_rows(), 2);
  r.write_row(30, {4.5});
  r.close();
  EXPECT_EQ(slurp(path), "step,a\n0,1\n10,2\n20,3\n30,4.5\n");
  std::remove(path.c_str());
}

// a redefined fix at the step its predecessor wrote last: nothing dropped, rows appended
TEST(CsvRecord, ResumeAtTheLastStepAppends)
{
  const std::string path = temp_path("append");
  spit(path, "step,a\n0,1\n10,2\n");
  CsvRecord r;
  r.resume(path, "step,a", 10);
  EXPECT_EQ(r.last_step(), 10);
  EXPECT_EQ(r.dropped_rows(), 0);
  r.write_row(20, {3});
  r.close();
  EXPECT_EQ(slurp(path), "step,a\n0,1\n10,2\n20,3\n");
  std::remove(path.c_str());
}

TEST(CsvRecord, ResumeOfAMissingOrEmptyFileStartsIt)
{
  const std::string path = temp_path("missing");
  std::remove(path.c_str());
  CsvRecord r;
  r.resume(path, "step,a", 100);
  EXPECT_EQ(r.last_step(), -1);
  r.close();
  EXPECT_EQ(slurp(path), "step,a\n");
  std::remove(path.c_str());
}

TEST(CsvRecord, ResumeWithOtherColumnsIsRefused)
{
  const std::string path = temp_path("columns");
  spit(path, "step,a\n0,1\n");
  CsvRecord r;
  EXPECT_THROW(r.resume(path, "step,a,b", 0), std::runtime_error);
  EXPECT_EQ(slurp(path), "step,a\n0,1\n");    // untouched
  std::remove(path.c_str());
}

// a full disk: the write fails at the flush and says so
TEST(CsvRecord, FailedWriteThrows)
{
  CsvRecord r;
  try {
    r.start("/dev/full", "step,a");
    FAIL() << "writing the header to /dev/full did not fail";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write to the record /dev/full"),
              std::string::npos) << e.what();
  }
  EXPECT_THROW(r.start("/nonexistent-dir/x.csv", "step"), std::runtime_error);
}
