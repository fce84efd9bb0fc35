// atomic_write / parent_directory / make_directory.
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

}  // namespace
}  // namespace emc::output
