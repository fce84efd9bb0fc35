// atomic_write / atomic_commit / make_directory.
#include <gtest/gtest.h>

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

TEST(AtomicCommit, RenamesTempOverTarget) {
  TempDir dir;
  const std::string tmp = dir / "b.bin.tmp.1", path = dir / "b.bin";
  atomic_write(path, "old");
  std::ofstream(tmp) << "new";
  atomic_commit(tmp, path);
  EXPECT_EQ(slurp(path), "new");
  EXPECT_EQ(list_dir(dir.path()), std::vector<std::string>{"b.bin"});
}

TEST(AtomicCommit, MissingTempThrowsNamingPath) {
  TempDir dir;
  const std::string path = dir / "c.bin";
  try {
    atomic_commit(dir / "c.bin.tmp.1", path);
    FAIL() << "no exception";
  } catch (const emc::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
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

}  // namespace
}  // namespace emc::output
