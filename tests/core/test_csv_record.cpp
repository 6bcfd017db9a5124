#include "csv_record.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
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

// `before` resumed at `step`, one row (step `next`, value 9) appended: the file afterwards
std::string resumed(const std::string& before, long long step, long long next,
                    long long expect_last, int expect_dropped)
{
  const std::string path = temp_path("resume");
  spit(path, before);
  CsvRecord r;
  r.resume(path, "step,a", step);
  EXPECT_EQ(r.last_step(), expect_last);
  EXPECT_EQ(r.dropped_rows(), expect_dropped);
  r.write_row(next, {9});
  r.close();
  const std::string after = slurp(path);
  std::remove(path.c_str());
  return after;
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
  EXPECT_EQ(resumed("step,a\n0,1\n10,2\n20,3\n30,4\n40,", 20, 30, 20, 2),
            "step,a\n0,1\n10,2\n20,3\n30,9\n");
}

// a redefined fix at the step its predecessor wrote last: nothing dropped, rows appended
TEST(CsvRecord, ResumeAtTheLastStepAppends)
{
  EXPECT_EQ(resumed("step,a\n0,1\n10,2\n", 10, 20, 10, 0), "step,a\n0,1\n10,2\n20,9\n");
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

// fix cell/servo's alias check: every name of one file has one identity, made or not yet made
TEST(FileIdentity, AliasesOfOneFileAreEqual)
{
  const std::string dir = ::testing::TempDir() + "alias" + std::to_string(::getpid());
  ASSERT_EQ(::mkdir(dir.c_str(), 0755), 0);
  ASSERT_EQ(::mkdir((dir + "/sub").c_str(), 0755), 0);
  const std::string file = dir + "/c.csv";
  // not yet made: the directory's identity plus the name
  EXPECT_EQ(tycore::file_identity(file), tycore::file_identity(dir + "/./c.csv"));
  EXPECT_EQ(tycore::file_identity(file), tycore::file_identity(dir + "/sub/../c.csv"));
  EXPECT_NE(tycore::file_identity(file), tycore::file_identity(dir + "/d.csv"));
  EXPECT_NE(tycore::file_identity(file), tycore::file_identity(dir + "/sub/c.csv"));
  spit(file, "step\n");
  ASSERT_EQ(::symlink(file.c_str(), (dir + "/link.csv").c_str()), 0);
  EXPECT_EQ(tycore::file_identity(file), tycore::file_identity(dir + "/link.csv"));
  EXPECT_EQ(tycore::file_identity(file), tycore::file_identity(dir + "/sub/../c.csv"));
  EXPECT_NE(tycore::file_identity(file), tycore::file_identity(dir + "/sub/c.csv"));
  // an open stream (a log file) and a path naming its file
  std::FILE* log = std::fopen(file.c_str(), "a");
  ASSERT_NE(log, nullptr);
  EXPECT_EQ(tycore::file_identity(log), tycore::file_identity(dir + "/./c.csv"));
  std::fclose(log);
  // a stream that is no regular file (a terminal, a pipe) names no path
  EXPECT_NE(tycore::file_identity(static_cast<std::FILE*>(nullptr)),
            tycore::file_identity(dir + "/d.csv"));
  std::remove((dir + "/link.csv").c_str());
  std::remove(file.c_str());
  ::rmdir((dir + "/sub").c_str());
  ::rmdir(dir.c_str());
}

// a restart or dump file per step ('*' in its name) is one of the pattern's files
TEST(FileIdentity, PathsOfAPatternPerStep)
{
  EXPECT_TRUE(tycore::names_file_of("r.restart.1000", "r.restart.*"));
  EXPECT_TRUE(tycore::names_file_of("./r.restart.1000", "r.restart.*"));
  EXPECT_TRUE(tycore::names_file_of("dump.5.txt", "./dump.*.txt"));
  EXPECT_FALSE(tycore::names_file_of("r.csv", "r.restart.*"));
  EXPECT_FALSE(tycore::names_file_of("sub/r.restart.10", "r.restart.*"));
  EXPECT_TRUE(tycore::names_file_of("./a.csv", "a.csv"));
}
