// The output directory's own files, its lock, safe temporaries, FieldWriter::resume and the
// directory held open (hostile and careless use of the output directory).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/directory.hpp"
#include "emcontact/output/fields.hpp"
#include "emcontact/output/monitors.hpp"
#include "emcontact/output/open_directory.hpp"
#include "emcontact/output/safe_temp.hpp"
#include "temp_dir.hpp"

namespace emc::output {
namespace {

using testing::list_dir;
using testing::slurp;
using testing::TempDir;

void touch(const std::string& path) {
  std::ofstream(path) << "x";
}

TEST(OutputDirectory, OwnedFilesAreExactlyOurs) {
  TempDir dir;
  for (const char* f : {"monitors.csv", "fields_00000010.h5", "notes.txt", "fields_x.h5",
                        "mesh.h5.bak", "checkpoint.h5", "fields_123456789.h5", "fields_0.h5",
                        "fields_0000001.h5", "fields_99999999999999999999.h5"})
    touch(dir / f);
  EXPECT_EQ(owned_files(dir.path()),
            (std::vector<std::string>{"checkpoint.h5", "fields_00000010.h5", "fields_123456789.h5",
                                      "monitors.csv"}));
}

TEST(OutputDirectory, RemoveOwnedFilesKeepsEverythingElse) {
  TempDir dir;
  for (const char* f : {"monitors.csv", "mesh.h5", "fields.xdmf", "fields_00000000.h5",
                        "energies.png", "monitors.csv.tmp.AbC123xyz789",
                        "energies.png.tmp.0123456789ab.png", "notes.txt", "run.log"})
    touch(dir / f);
  // names that only look like ours: a frame's step not as fields_%08ld.h5 writes it, a
  // temporary's suffix not as create_temp makes it
  const std::vector<std::string> lookalikes = {"fields_0.h5",
                                               "fields_0000001.h5",
                                               "fields_99999999999999999999.h5",
                                               "fields_-0000001.h5",
                                               "fields_+0000001.h5",
                                               "mesh.h5.tmp.x",
                                               "mesh.h5.tmp.AbC123xyz78",
                                               "mesh.h5.tmp.AbC123xyz789.bak",
                                               "energies.png.tmp.0123456789ab",
                                               "monitors.csv.tmp.AbC123xyz7_9"};
  for (const auto& f : lookalikes) touch(dir / f);
  std::filesystem::create_directory(dir / "fields_00000001.h5");
  TempDir elsewhere;
  touch(elsewhere / "victim");
  std::filesystem::create_symlink(elsewhere / "victim", dir / "checkpoint.h5");
  remove_owned_files(dir.path());
  std::vector<std::string> kept = lookalikes;
  for (const char* f : {"fields_00000001.h5", "notes.txt", "run.log"}) kept.push_back(f);
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(list_dir(dir.path()), kept);
  EXPECT_EQ(slurp(elsewhere / "victim"), "x");  // the link went, not its target
}

TEST(OutputDirectory, SecondLockFailsNamingTheDirectory) {
  TempDir dir;
  DirectoryLock first(dir.path());
  try {
    DirectoryLock second(dir.path());
    FAIL() << "a second lock was granted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir.path()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
  }
  first = DirectoryLock();  // released
  EXPECT_NO_THROW(DirectoryLock again(dir.path()));
}

TEST(OutputDirectory, LinkAtTheLockIsRefused) {
  TempDir dir;
  touch(dir / "target");
  std::filesystem::create_symlink(dir / "target", dir / ".emcontact.lock");
  EXPECT_THROW(DirectoryLock lock(dir.path()), Error);
  EXPECT_EQ(slurp(dir / "target"), "x");
}

TEST(SafeTemp, FreshUnpredictableNamesCreatedExclusively) {
  TempDir dir;
  const Directory d(dir.path());
  const TempFile a = create_temp(d, "f"), b = create_temp(d, "f");
  EXPECT_NE(a.name, b.name);
  EXPECT_EQ(a.name.rfind("f.tmp.", 0), 0u);
  struct stat st {};
  ASSERT_EQ(::lstat((dir / a.name).c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode));
  ::close(a.fd);
  ::close(b.fd);
}

TEST(AtomicWrite, ReplacesALinkAtTheTargetNotItsTarget) {
  TempDir dir;
  touch(dir / "victim");
  std::filesystem::create_symlink(dir / "victim", dir / "monitors.csv");
  atomic_write(dir / "monitors.csv", "new");
  EXPECT_EQ(slurp(dir / "victim"), "x");
  EXPECT_FALSE(std::filesystem::is_symlink(dir / "monitors.csv"));
  EXPECT_EQ(slurp(dir / "monitors.csv"), "new");
}

FieldFrame frame(long step, std::size_t nodes, std::size_t tets) {
  FieldFrame f;
  f.step = step;
  f.time = 0.5 * step;
  f.displacement.assign(3 * nodes, 0.0);
  f.velocity.assign(3 * nodes, 0.0);
  f.von_mises.assign(tets, 0.0);
  return f;
}

TEST(FieldWriterResume, KeepsFramesUpToTheStepAndRemovesLaterOnes) {
  TempDir dir;
  const std::vector<double> X = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<long long> tets = {0, 1, 2, 3};
  const std::vector<int> body = {0};
  {
    FieldWriter w(dir.path(), X, tets, body);
    for (long s = 0; s <= 4; ++s) w.write(frame(s, 4, 1));
  }
  touch(dir / "fields_00000003.h5.notes");
  FieldWriter w(dir.path(), X, tets, body);
  w.resume(2);
  const std::string xdmf = slurp(dir / "fields.xdmf");
  for (long s : {0L, 1L, 2L})
    EXPECT_NE(xdmf.find("step_" + std::to_string(s) + "\""), std::string::npos) << s;
  EXPECT_EQ(xdmf.find("step_3\""), std::string::npos);
  EXPECT_NE(xdmf.find("<Time Value=\"1\"/>"), std::string::npos);  // time of step 2 read back
  EXPECT_FALSE(std::filesystem::exists(dir / "fields_00000003.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "fields_00000004.h5"));
  EXPECT_TRUE(std::filesystem::exists(dir / "fields_00000003.h5.notes"));
  w.write(frame(3, 4, 1));
  EXPECT_NE(slurp(dir / "fields.xdmf").find("step_3\""), std::string::npos);
}

// The directory held open: renamed, with a link to another directory planted at its old name,
// it still gets every write, listing and removal (the link's target gets none).
TEST(Directory, WritesFollowTheOpenedDirectoryNotItsName) {
  TempDir parent, elsewhere;
  const std::string name = parent / "out", moved = parent / "moved";
  std::filesystem::create_directory(name);
  const Directory d(name);
  const DirectoryLock lock(d);
  std::filesystem::rename(name, moved);
  std::filesystem::create_directory_symlink(elsewhere.path(), name);
  atomic_write(d, "monitors.csv", "rows");
  MonitorWriter w(d, "monitors.csv");
  w.flush();
  const std::vector<double> X = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  FieldWriter f(d, X, {0, 1, 2, 3}, {0});
  f.write(frame(0, 4, 1));
  EXPECT_EQ(owned_files(d), (std::vector<std::string>{"fields.xdmf", "fields_00000000.h5",
                                                      "mesh.h5", "monitors.csv"}));
  EXPECT_TRUE(list_dir(elsewhere.path()).empty());
  EXPECT_EQ(list_dir(moved),
            (std::vector<std::string>{".emcontact.lock", "fields.xdmf", "fields_00000000.h5",
                                      "mesh.h5", "monitors.csv"}));
  remove_owned_files(d);
  EXPECT_EQ(list_dir(moved), (std::vector<std::string>{".emcontact.lock"}));
}

TEST(Directory, ALinkAsTheDirectoryIsRefusedNamingIt) {
  TempDir parent;
  std::filesystem::create_directory(parent / "real");
  std::filesystem::create_directory_symlink(parent / "real", parent / "link");
  // a trailing slash (shell completion adds one) or "/." names the link too
  for (const char* given : {"link", "link/", "link//", "link/.", "link/./"}) {
    try {
      const Directory d(parent / given);
      FAIL() << "the link was followed for '" << given << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("symbolic link"), std::string::npos) << e.what();
    }
  }
  for (const char* given : {"real", "real/", "real/."}) EXPECT_NO_THROW(Directory(parent / given));
  EXPECT_NO_THROW(Directory("/"));
}

}  // namespace
}  // namespace emc::output
