// The CSV record of a test (fix cell/servo's `csv FILE N`): one header line of column names,
// then one row per output step, the step number first. Plain C++ (no LAMMPS), so that the
// rules a record keeps are tested directly (tests/core/test_csv_record.cpp):
//  * every write is checked and flushed: a full disk or a closed pipe is an error
//    (std::runtime_error), never a silently short record;
//  * a new test starts its record (the file is created or emptied, the header written);
//  * a continued test (a redefined fix, or a run resumed from a restart file) appends to the
//    record it continues: the header must be the same; rows of steps after the step it resumes
//    at (written by a run that crashed after its last restart file) and a torn last line are
//    superseded by the rows the resumed run writes, so the steps never repeat or go back.
#ifndef TYCORE_CSV_RECORD_HPP
#define TYCORE_CSV_RECORD_HPP

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <fnmatch.h>
#include <sys/stat.h>

namespace tycore {

class CsvRecord {
 public:
  CsvRecord() = default;
  CsvRecord(const CsvRecord &) = delete;
  CsvRecord &operator=(const CsvRecord &) = delete;
  ~CsvRecord() { close(); }

  bool is_open() const { return file_ != nullptr; }
  const std::string &path() const { return path_; }
  // step of the last row in the file (-1 without rows)
  long long last_step() const { return last_step_; }
  // rows removed when continuing (superseded rows and a torn line)
  int dropped_rows() const { return dropped_; }

  void start(const std::string &path, const std::string &header)
  {
    close();
    path_ = path;
    file_ = std::fopen(path.c_str(), "w");
    if (!file_) fail("cannot open");
    last_step_ = -1;
    dropped_ = 0;
    write_text(header + "\n");
  }

  void resume(const std::string &path, const std::string &header, long long current_step)
  {
    close();
    path_ = path;
    last_step_ = -1;
    dropped_ = 0;
    std::string text;
    if (std::FILE *in = std::fopen(path.c_str(), "r")) {
      char buffer[65536];
      std::size_t n;
      while ((n = std::fread(buffer, 1, sizeof buffer, in)) > 0) text.append(buffer, n);
      const bool bad = std::ferror(in) != 0;
      std::fclose(in);
      if (bad) fail("cannot read");
    }
    if (text.empty()) {
      start(path, header);
      return;
    }
    const std::size_t header_end = text.find('\n');
    if (header_end == std::string::npos || text.compare(0, header_end, header) != 0)
      throw std::runtime_error("the record " + path +
                               " has other columns than this test "
                               "writes (its header differs): continue it with the same "
                               "columns, or write to another file");
    // keep complete rows up to the current step
    std::size_t keep = header_end + 1, pos = keep;
    while (pos < text.size()) {
      const std::size_t end = text.find('\n', pos);
      if (end == std::string::npos) {    // torn last line (a crash while writing it)
        ++dropped_;
        break;
      }
      const long long step = std::strtoll(text.c_str() + pos, nullptr, 10);
      if (step > current_step) {    // written after the state this run resumes from
        for (std::size_t p = pos; p < text.size(); ++p) dropped_ += text[p] == '\n';
        dropped_ += text.back() != '\n';
        break;
      }
      last_step_ = step;
      keep = pos = end + 1;
    }
    if (keep < text.size()) {
      std::error_code ec;
      std::filesystem::resize_file(path, keep, ec);
      if (ec) throw std::runtime_error("cannot shorten the record " + path + ": " + ec.message());
    }
    file_ = std::fopen(path.c_str(), "a");
    if (!file_) fail("cannot open");
  }

  // one row: the step, then the values with 12 significant digits
  void write_row(long long step, const std::vector<double> &values)
  {
    std::string line = std::to_string(step);
    char number[32];
    for (double v : values) {
      std::snprintf(number, sizeof number, ",%.12g", v);
      line += number;
    }
    write_text(line + "\n");
    last_step_ = step;
  }

  void close()
  {
    if (file_) std::fclose(file_);
    file_ = nullptr;
  }

 private:
  [[noreturn]] void fail(const char *what) const
  {
    throw std::runtime_error(std::string(what) + " the record " + path_ + ": " +
                             std::strerror(errno));
  }

  void write_text(const std::string &text)
  {
    if (!file_) throw std::runtime_error("the record " + path_ + " is not open");
    errno = 0;
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
      fail("cannot write to");
  }

  std::FILE *file_ = nullptr;
  std::string path_;
  long long last_step_ = -1;
  int dropped_ = 0;
};

// Which file a path names, so that two names of one record are recognised as one (fix
// cell/servo refuses to start a record over another it would overwrite): an existing file is
// its device and inode, whatever its name (./c.csv, c.csv, a symbolic link, d/../c.csv); a
// file not yet made is the device and inode of its directory (symbolic links and .. resolved)
// plus its name. Two paths alias when their identities are equal.
struct FileIdentity {
  unsigned long long device = 0, inode = 0;
  std::string name;    // empty for an existing file; the file name in its directory otherwise
  bool operator==(const FileIdentity &o) const
  {
    return device == o.device && inode == o.inode && name == o.name;
  }
  bool operator!=(const FileIdentity &o) const { return !(*this == o); }
};

inline FileIdentity identity_of(const struct stat &st, const std::string &name = "")
{
  return {static_cast<unsigned long long>(st.st_dev), static_cast<unsigned long long>(st.st_ino),
          name};
}

inline FileIdentity file_identity(const std::string &path)
{
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) return identity_of(st);
  std::error_code ec;
  const std::filesystem::path full =
      std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  const std::filesystem::path dir = full.parent_path();
  if (::stat(dir.empty() ? "." : dir.c_str(), &st) == 0)
    return identity_of(st, full.filename().string());
  return {0, 0, full.string()};    // no such directory: nothing else can be written there
}

// the file an open stream writes to or reads from (a log file, the input script)
inline FileIdentity file_identity(std::FILE *stream)
{
  struct stat st;
  if (stream && ::fstat(fileno(stream), &st) == 0 && S_ISREG(st.st_mode)) return identity_of(st);
  return {};    // (0, 0, ""): equal to no path's identity
}

// a path names one of the files of a pattern with '*' (a file per step: restart files,
// dumps), or, without '*', the pattern's file: the same directory and a matching name
inline bool names_file_of(const std::string &path, const std::string &pattern)
{
  if (pattern.find('*') == std::string::npos) return file_identity(path) == file_identity(pattern);
  const std::filesystem::path p(path), q(pattern);
  const auto directory = [](const std::filesystem::path &f) {
    return f.has_parent_path() ? f.parent_path().string() : std::string(".");
  };
  return file_identity(directory(p)) == file_identity(directory(q)) &&
      ::fnmatch(q.filename().c_str(), p.filename().c_str(), 0) == 0;
}

}    // namespace tycore

#endif
