// atomic_write / parent_directory / make_directory / GrowingFile.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <fstream>
#include <string>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "temp_dir.hpp"

namespace emc::output {
namespace {

using testing::has_temp_file;
using testing::list_dir;
using testing::slurp;
using testing::TempDir;

TEST(AtomicWrite, WritesContentAndLeavesNoTempFile) {
  TempDir dir;
  const std::string path = dir / "a.txt";
  atomic_write(path, "hello\n");
  EXPECT_EQ(slurp(path), "hello\n");
  EXPECT_EQ(list_dir(dir.path()), std::vector<std::string>{"a.txt"});
}

TEST(AtomicWrite, ReplacesExistingFile) {
  TempDir dir;
  const std::string path = dir / "a.txt";
  atomic_write(path, std::string(100000, 'x'));
  atomic_write(path, "short");
  EXPECT_EQ(slurp(path), "short");
  EXPECT_FALSE(has_temp_file(dir.path()));
}

TEST(AtomicWrite, EmptyContent) {
  TempDir dir;
  atomic_write(dir / "empty", "");
  EXPECT_EQ(slurp(dir / "empty"), "");
  EXPECT_EQ(list_dir(dir.path()), std::vector<std::string>{"empty"});
}

TEST(AtomicWrite, MissingDirectoryThrowsNamingPathAndOsError) {
  TempDir dir;
  const std::string path = dir / "no/such/dir/file.csv";
  try {
    atomic_write(path, "x");
    FAIL() << "no exception";
  } catch (const emc::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("No such file or directory"), std::string::npos) << what;
  }
  EXPECT_TRUE(list_dir(dir.path()).empty());
}

TEST(ParentDirectory, OfRelativeAbsoluteAndBareNames) {
  EXPECT_EQ(parent_directory("out/monitors.csv"), "out");
  EXPECT_EQ(parent_directory("/checkpoint.h5"), "/");
  EXPECT_EQ(parent_directory("checkpoint.h5"), ".");
  EXPECT_EQ(parent_directory("a/b/c.h5"), "a/b");
}

TEST(MakeDirectory, CreatesParentsAndIsIdempotent) {
  TempDir dir;
  const std::string nested = dir / "a/b/c";
  make_directory(nested);
  make_directory(nested);        // exists: fine
  make_directory(nested + "/");  // trailing slash: fine
  atomic_write(nested + "/f", "ok");
  EXPECT_EQ(slurp(nested + "/f"), "ok");
}

TEST(MakeDirectory, FileInTheWayThrowsNamingDirectory) {
  TempDir dir;
  atomic_write(dir / "file", "x");
  for (const std::string& target : {dir / "file", dir / "file/sub"}) {
    try {
      make_directory(target);
      FAIL() << "no exception for " << target;
    } catch (const emc::Error& e) {
      EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
    }
  }
}

TEST(GrowingFile, WritesOverItsEndAndAppends) {
  TempDir dir;
  GrowingFile f;
  f.replace(Directory(dir.path()), "index.xml", "<a>\n</a>\n");
  f.write_at(4, "  <b/>\n</a>\n");  // over the closing tag
  f.write_at(f.size(), "tail\n");
  EXPECT_EQ(slurp(dir / "index.xml"), "<a>\n  <b/>\n</a>\ntail\n");
  EXPECT_EQ(f.size(), slurp(dir / "index.xml").size());
  f.write_at(4, "</a>\n");  // shorter than what it overwrites: the file is cut there
  EXPECT_EQ(slurp(dir / "index.xml"), "<a>\n</a>\n");
  EXPECT_FALSE(has_temp_file(dir.path()));
}

TEST(GrowingFile, AFailedWriteLeavesTheFileAsItWas) {
  TempDir dir;
  GrowingFile f;
  const std::string start(1000, 'a');
  f.replace(Directory(dir.path()), "m.csv", start);
  // a file size limit stands in for a full disk: the write fails part way (EFBIG)
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  auto* previous = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 1500;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  bool threw = false;
  try {
    f.write_at(f.size(), std::string(2000, 'b'));
  } catch (const Error& e) {
    threw = std::string(e.what()).find(dir / "m.csv") != std::string::npos;
  }
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &old), 0);
  std::signal(SIGXFSZ, previous);
  EXPECT_TRUE(threw) << "no error naming the file";
  EXPECT_EQ(slurp(dir / "m.csv"), start);
  EXPECT_EQ(f.size(), start.size());
}

}  // namespace
}  // namespace emc::output
