// Output folders replaced as one unit, temporary names of dead runs, checked number formatting.
#include "geometry/atomic_file.hpp"
#include "geometry/folder_ops.hpp"
#include "tests/geometry/test_files.hpp"
#include "geometry/run_files.hpp"
#include "geometry/staged_folder.hpp"
#include "geometry/text_out.hpp"

#include <doctest/doctest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

using namespace canopy;
namespace fs = std::filesystem;

using canopy::testing::slurp;

namespace {

// A pid above any the kernel hands out (pid_max is at most 2^22): a process that has ended.
const std::string kDeadTag = "1073741000-5";

std::string temp_dir() { return canopy::testing::temp_dir("folder"); }

void put(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::set<std::string> names(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

ino_t inode(const fs::path& p) {
  struct stat st;
  REQUIRE(::lstat(p.c_str(), &st) == 0);
  return st.st_ino;
}

const std::vector<std::string> kStand{"organs.csv", "plants.csv", "report.json", "stand.ply", "light.csv"};

void write_set(const std::string& dir, const std::string& tag,
               std::vector<std::string> files = {"organs.csv", "plants.csv"}) {
  OutputSet set(dir, kStand);
  for (const std::string& f : files) set.open(f).write(tag);
  set.commit_all();
}

}  // namespace

TEST_CASE("a new folder: made only when the set is complete, nothing left beside it") {
  const fs::path root = temp_dir();
  const std::string dir = (root / "a" / "b" / "out").string();
  {
    OutputSet set(dir, kStand);
    set.open("organs.csv").write("1");
    CHECK_FALSE(fs::exists(dir));  // the files are in the staging folder until the swap
    set.commit_all();
  }
  CHECK(names(dir) == std::set<std::string>{"organs.csv"});
  CHECK(names(root / "a" / "b") == std::set<std::string>{"out"});
  // Not committed (a failed run): the folder, and the folders made above it, are not there.
  const std::string other = (root / "c" / "d" / "out").string();
  {
    OutputSet set(other, kStand);
    set.open("organs.csv").write("partial");
  }
  CHECK_FALSE(fs::exists(root / "c"));
  CHECK(names(root) == std::set<std::string>{"a"});
  fs::remove_all(root);
}

TEST_CASE("a replaced folder keeps the user's files and folders, drops the earlier set") {
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  write_set(dir.string(), "old", {"organs.csv", "plants.csv", "report.json", "stand.ply"});
  put(dir / "notes.txt", "mine");
  put(dir / "light.csv", "light of the old stand");
  put(dir / ("stand.glb.tmp-" + kDeadTag), "debris of a dead run");
  fs::create_directories(dir / "renders" / "deep");
  put(dir / "renders" / "deep" / "a.png", "picture");
  const ino_t notes = inode(dir / "notes.txt");
  fs::permissions(dir, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);  // 0750, kept
  StagedFolder::Committed c;
  {
    OutputSet set(dir.string(), kStand);
    set.open("organs.csv").write("new");
    set.open("plants.csv").write("new");
    c = set.commit_all();
  }
  CHECK(names(dir) == std::set<std::string>{"notes.txt", "organs.csv", "plants.csv", "renders"});
  CHECK(slurp(dir / "organs.csv") == "new");
  CHECK(inode(dir / "notes.txt") == notes);  // the same file, never copied
  CHECK(fs::status(dir).permissions() ==
        (fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec));
  CHECK(slurp(dir / "renders" / "deep" / "a.png") == "picture");
  CHECK(std::set<std::string>(c.dropped.begin(), c.dropped.end()) ==
        std::set<std::string>{"light.csv", "report.json", "stand.ply"});
  CHECK(c.notes.empty());
  CHECK(names(root) == std::set<std::string>{"out"});
  fs::remove_all(root);
}

TEST_CASE("a folder under a name of the set is refused before any work, the folder as it was") {
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  write_set(dir.string(), "old");
  fs::create_directories(dir / "stand.ply" / "mine");
  put(dir / "stand.ply" / "mine" / "a.txt", "kept");
  CHECK_THROWS_WITH(
      OutputSet(dir.string(), kStand),
      doctest::Contains("stand.ply is a folder there, under the name of one of the folder's files"));
  CHECK(names(dir) == std::set<std::string>{"organs.csv", "plants.csv", "stand.ply"});
  CHECK(slurp(dir / "stand.ply" / "mine" / "a.txt") == "kept");
  CHECK(names(root) == std::set<std::string>{"out"});  // no staging folder
  // A folder of another name is the user's, carried across.
  fs::rename(dir / "stand.ply", dir / "renders");
  write_set(dir.string(), "new");
  CHECK(slurp(dir / "renders" / "mine" / "a.txt") == "kept");
  CHECK(slurp(dir / "organs.csv") == "new");
  // A set that names none of its files (only what it writes is known) is refused when it swaps
  // the folder in: the folder under a new file's name went with the earlier folder, and was removed.
  fs::create_directories(dir / "light.json" / "mine");
  put(dir / "light.json" / "mine" / "b.txt", "kept too");
  const std::set<std::string> before = names(dir);
  {
    OutputSet light(dir.string());
    light.open("light.json").write("{}");
    CHECK_THROWS_WITH(light.commit_all(), doctest::Contains("cannot put light.json into"));
  }
  CHECK(slurp(dir / "light.json" / "mine" / "b.txt") == "kept too");
  CHECK(slurp(dir / "renders" / "mine" / "a.txt") == "kept");
  CHECK(names(dir) == before);
  CHECK(names(root) == std::set<std::string>{"out"});
  fs::remove_all(root);
}

TEST_CASE("files made from a folder that another run replaced meanwhile are not put in") {
  // canopy light DIR reads the stand and adds its light; a stand written to DIR in between would
  // have taken a light made for the stand before it.
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  write_set(dir.string(), "first", {"organs.csv", "plants.csv"});
  const FolderIdentity read = folder_identity(dir.string(), "organs.csv");
  CHECK(read.ino == inode(dir));
  CHECK(read.file_ino == inode(dir / "organs.csv"));
  CHECK(folder_identity((root / "none").string()) == FolderIdentity{});
  {
    OutputSet same(dir.string());  // nothing replaced it: the light joins the stand
    same.require_folder(read, "organs.csv");
    same.open("light.csv").write("light of the first");
    same.commit_all();
  }
  CHECK(slurp(dir / "light.csv") == "light of the first");
  CHECK(slurp(dir / "organs.csv") == "first");
  const FolderIdentity second_read = folder_identity(dir.string(), "organs.csv");  // a new folder
  write_set(dir.string(), "second", {"organs.csv", "plants.csv"});  // another run, meanwhile
  {
    OutputSet late(dir.string());
    late.require_folder(second_read, "organs.csv");
    late.open("light.csv").write("light of the first, again");
    CHECK_THROWS_WITH(late.commit_all(), doctest::Contains("was replaced by another run while this one read it"));
  }
  CHECK(slurp(dir / "organs.csv") == "second");
  CHECK(!fs::exists(dir / "light.csv"));  // the second stand dropped the first's light; this one is not put in
  CHECK(names(root) == std::set<std::string>{"out"});  // no staging folder left
  fs::remove_all(dir);
  {
    OutputSet gone(dir.string());  // the folder removed meanwhile: nothing made in its place
    gone.require_folder(second_read, "organs.csv");
    gone.open("light.csv").write("x");
    CHECK_THROWS(gone.commit_all());
  }
  CHECK(names(root).empty());
  fs::remove_all(root);
}

TEST_CASE("a set's files have no name until the set is complete") {
  const fs::path root = temp_dir();
  const fs::path dir = root / "a" / "out";
  OutputSet set(dir.string(), kStand);
  if (!set.folder().unnamed_file_possible()) {
    MESSAGE("unnamed files are not made on this file system: the files are named in a staging folder");
    return;
  }
  set.open("organs.csv").write("half of a");
  set.open("plants.csv").write("table");
  CHECK(names(root).empty());  // no staging folder, not even the folder above the output
  set.commit_all();
  CHECK(names(root) == std::set<std::string>{"a"});
  CHECK(names(dir) == std::set<std::string>{"organs.csv", "plants.csv"});
  CHECK(slurp(dir / "organs.csv") == "half of a");
  fs::remove_all(root);
}

TEST_CASE("a set that writes a file the folder has replaces it, leaving nothing beside the folder") {
  // canopy light's set: no list of files it replaces, only the files it writes again.
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  write_set(dir.string(), "stand", {"organs.csv", "plants.csv"});
  for (const char* tag : {"first", "second"}) {
    OutputSet set(dir.string());
    set.open("light.csv").write(tag);
    set.open("light.json").write(tag);
    CHECK(set.commit_all().notes.empty());
    CHECK(names(dir) == std::set<std::string>{"light.csv", "light.json", "organs.csv", "plants.csv"});
    CHECK(slurp(dir / "light.csv") == tag);
    CHECK(slurp(dir / "organs.csv") == "stand");
    CHECK(names(root) == std::set<std::string>{"out"});
  }
  fs::remove_all(root);
}

TEST_CASE("a folder without the set's marker holds no earlier set: its files of those names are kept") {
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  fs::create_directories(dir);
  put(dir / "stand.ply", "the user's own mesh");
  put(dir / "report.json", "the user's notes");
  StagedFolder::Committed c;
  {
    OutputSet set(dir.string(), kStand, "organs.csv");
    set.open("organs.csv").write("new");
    set.open("report.json").write("new");
    c = set.commit_all();
  }
  CHECK(names(dir) == std::set<std::string>{"organs.csv", "report.json", "stand.ply"});
  CHECK(slurp(dir / "stand.ply") == "the user's own mesh");  // not written again: kept
  CHECK(slurp(dir / "report.json") == "new");                // written again: replaced
  CHECK(c.dropped.empty());
  // Once the folder holds a set (its marker), the set's files go with it.
  {
    OutputSet set(dir.string(), kStand, "organs.csv");
    set.open("organs.csv").write("newer");
    c = set.commit_all();
  }
  CHECK(names(dir) == std::set<std::string>{"organs.csv"});
  CHECK(names(root) == std::set<std::string>{"out"});
  fs::remove_all(root);
}

TEST_CASE("a symbolic link to the folder stays, its target is replaced") {
  const fs::path root = temp_dir();
  write_set((root / "real").string(), "old");
  fs::create_directory_symlink("real", root / "link");
  write_set((root / "link").string(), "new");
  CHECK(fs::is_symlink(root / "link"));
  CHECK(slurp(root / "link" / "organs.csv") == "new");
  CHECK(names(root) == std::set<std::string>{"link", "real"});
  fs::remove_all(root);
}

TEST_CASE("what dead runs left beside the folder is removed, the user's things put back") {
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  write_set(dir.string(), "old");
  put(dir / "notes.txt", "mine");
  // A run killed between carrying the earlier folder's entries across and its swap: its new set,
  // a link to the user's file, the user's folder moved in.
  const fs::path dead = root / (".out.canopy-" + kDeadTag + "-0");
  fs::create_directory(dead);
  put(dead / "organs.csv", "unfinished");
  fs::create_hard_link(dir / "notes.txt", dead / "notes.txt");
  fs::create_directories(dead / "renders");
  put(dead / "renders" / "a.png", "picture");
  // A live process's staging folder is left alone (this process's tag, another count).
  const fs::path live = root / (".out.canopy-" + process_tag() + "-999");
  fs::create_directory(live);
  std::vector<std::string> removed;
  {
    StagedFolder f(dir.string(), kStand);
    removed = f.leftovers_removed();
    CHECK(f.leftover_notes().empty());
  }
  CHECK(removed == std::vector<std::string>{dead.filename().string()});
  CHECK_FALSE(fs::exists(dead));
  CHECK(fs::exists(live));
  CHECK(names(dir) == std::set<std::string>{"notes.txt", "organs.csv", "plants.csv", "renders"});
  CHECK(slurp(dir / "renders" / "a.png") == "picture");
  CHECK(slurp(dir / "organs.csv") == "old");
  // Where renames stood in for the exchange and the run died between them: the earlier folder,
  // moved aside, goes back.
  fs::remove(live);
  const fs::path aside = root / (".out.canopy-" + kDeadTag + "-1-old");
  fs::rename(dir, aside);
  { StagedFolder f(dir.string(), kStand); }
  CHECK(slurp(dir / "organs.csv") == "old");
  CHECK(names(root) == std::set<std::string>{"out"});
  fs::remove_all(root);
}

TEST_CASE("readers never see a mix of two sets") {
  // A writer replaces a folder's two files, both naming the same run, while a reader reads them
  // as canopy detect and canopy render do (read_stand: open_in_one_set).
  const fs::path root = temp_dir();
  const std::string dir = (root / "out").string();
  write_set(dir, "run 0");
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (int k = 1; k <= 300; ++k) write_set(dir, "run " + std::to_string(k));
    stop = true;
  });
  int mixed = 0, reads = 0;
  while (!stop) {
    std::ifstream a, b;
    open_in_one_set(dir, {&a, &b}, {dir + "/organs.csv", dir + "/plants.csv"});
    if (!a || !b) continue;  // between a swap and the earlier folder's removal the files may be gone
    std::ostringstream sa, sb;
    sa << a.rdbuf(), sb << b.rdbuf();
    ++reads;
    if (sa.str() != sb.str()) ++mixed;
  }
  writer.join();
  CHECK(reads > 0);
  CHECK(mixed == 0);
  CHECK(names(root) == std::set<std::string>{"out"});
  fs::remove_all(root);
}

TEST_CASE("readers never see a mix of two sets written in place") {
  // The working folder: its files are moved in one by one, which a reader waits out, and each
  // file it opened is checked again after opening them all.
  const fs::path root = temp_dir();
  const std::string dir = (root / "out").string();
  write_set(dir, "run 0");
  const fs::path here = fs::current_path();
  fs::current_path(dir);
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (int k = 1; k <= 300; ++k) write_set(".", "run " + std::to_string(k));
    stop = true;
  });
  int mixed = 0, reads = 0;
  while (!stop) {
    std::ifstream a, b;
    open_in_one_set(dir, {&a, &b}, {dir + "/organs.csv", dir + "/plants.csv"});
    if (!a || !b) continue;
    std::ostringstream sa, sb;
    sa << a.rdbuf(), sb << b.rdbuf();
    ++reads;
    if (sa.str() != sb.str()) ++mixed;
  }
  writer.join();
  fs::current_path(here);
  CHECK(reads > 0);
  CHECK(mixed == 0);
  CHECK(names(root) == std::set<std::string>{"out"});
  CHECK(names(dir) == std::set<std::string>{"organs.csv", "plants.csv"});
  fs::remove_all(root);
}

TEST_CASE("output folders that cannot be replaced as a whole are refused up front") {
  const fs::path root = temp_dir();
  put(root / "file", "x");
  CHECK_THROWS_WITH_AS(check_output_dir((root / "file").string()),
                       doctest::Contains("it exists and is not a folder"), std::runtime_error);
  // Links that lead to no folder say where they lead (all three said 'exists and is not a folder').
  fs::create_symlink(root / "gone", root / "dangling");
  CHECK_THROWS_WITH_AS(
      check_output_dir((root / "dangling").string()),
      doctest::Contains(("a symbolic link to " + (root / "gone").string() + ", which is not there").c_str()),
      std::runtime_error);
  fs::create_symlink(root / "loop_b", root / "loop_a");
  fs::create_symlink(root / "loop_a", root / "loop_b");
  CHECK_THROWS_WITH_AS(check_output_dir((root / "loop_a").string()),
                       doctest::Contains("a symbolic link in a loop of links"), std::runtime_error);
  fs::create_symlink(root / "file", root / "to_file");
  CHECK_THROWS_WITH_AS(check_output_dir((root / "to_file").string()),
                       doctest::Contains("which is not a folder"), std::runtime_error);
  for (const char* l : {"dangling", "loop_a", "loop_b", "to_file"}) fs::remove(root / l);
  CHECK_THROWS_WITH_AS(check_output_dir("/"), doctest::Contains("the file system's root cannot be replaced"),
                       std::runtime_error);
  CHECK_THROWS_AS(check_output_dir("/proc/canopy-cannot-write-here"), std::runtime_error);
  const fs::path here = fs::current_path();
  fs::current_path(root);
  CHECK_NOTHROW(check_output_dir("sub/new"));
  fs::current_path(here);
  CHECK(names(root) == std::set<std::string>{"file"});  // the checks leave nothing behind
  fs::remove_all(root);
}

TEST_CASE("the working folder is written in place: the same folder, one set, what a kill left finished") {
  // A shell in the folder stays in it: the folder is not swapped but its files replaced.
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  write_set(dir.string(), "old", {"organs.csv", "plants.csv", "stand.ply"});
  put(dir / "notes.txt", "mine");
  const ino_t folder = inode(dir), notes = inode(dir / "notes.txt");
  const fs::path here = fs::current_path();
  fs::current_path(dir);
  CHECK_NOTHROW(check_output_dir("."));
  StagedFolder::Committed c;
  {
    OutputSet set(".", kStand);
    set.open("organs.csv").write("new");
    set.open("plants.csv").write("new");
    c = set.commit_all();
  }
  CHECK(inode(dir) == folder);
  CHECK(names(dir) == std::set<std::string>{"notes.txt", "organs.csv", "plants.csv"});
  CHECK(slurp(dir / "organs.csv") == "new");
  CHECK(inode(dir / "notes.txt") == notes);
  CHECK(c.dropped == std::vector<std::string>{"stand.ply"});
  {
    // Written in place, the folder stays the folder: its stand file tells a replaced stand.
    const FolderIdentity read = folder_identity(".", "organs.csv");
    write_set(".", "another", {"organs.csv", "plants.csv"});
    OutputSet light(".");
    light.require_folder(read, "organs.csv");
    light.open("light.csv").write("light of the stand before");
    CHECK_THROWS_WITH(light.commit_all(), doctest::Contains("was replaced by another run"));
  }
  CHECK(names(dir) == std::set<std::string>{"notes.txt", "organs.csv", "plants.csv"});
  {
    // A folder where a file goes: refused before any work; one made during the run is found
    // before any file moves. The folder as it was, either way.
    fs::create_directory(dir / "report.json");
    CHECK_THROWS_WITH(OutputSet(".", kStand), doctest::Contains("report.json is a folder there"));
    fs::remove(dir / "report.json");
    OutputSet blocked(".", kStand);
    blocked.open("organs.csv").write("blocked");
    blocked.open("report.json").write("blocked");
    fs::create_directory(dir / "report.json");
    CHECK_THROWS_WITH(blocked.commit_all(), doctest::Contains("cannot put report.json into .: a folder of that name is there"));
    fs::remove(dir / "report.json");
  }
  CHECK(slurp(dir / "organs.csv") == "another");
  {
    OutputSet failed(".", kStand);  // not committed: nothing of it stays
    failed.open("organs.csv").write("torn");
  }
  CHECK(names(dir) == std::set<std::string>{"notes.txt", "organs.csv", "plants.csv"});
  CHECK(slurp(dir / "organs.csv") == "another");
  // A run killed while moving its files in left its list and the files not yet moved: the next
  // run finishes that move (one set again), then writes its own.
  fs::create_directory(dir / (".canopy-" + kDeadTag + "-0"));
  put(dir / (".canopy-" + kDeadTag + "-0") / "plants.csv", "killed");
  put(dir / (".canopy-" + kDeadTag + "-0") / ".canopy-commit", "organs.csv\n");
  fs::create_directory(dir / (".canopy-" + kDeadTag + "-1"));  // killed before its files were complete
  put(dir / (".canopy-" + kDeadTag + "-1") / "organs.csv", "half");
  {
    OutputSet next(".", kStand);
    CHECK(names(dir) == std::set<std::string>{"notes.txt", "plants.csv"});
    CHECK(slurp(dir / "plants.csv") == "killed");
    CHECK(next.folder().leftovers_removed().size() == 2);
    next.open("report.json").write("next");
    next.commit_all();
  }
  CHECK(names(dir) == std::set<std::string>{"notes.txt", "report.json"});
  fs::current_path(here);
  CHECK(names(root) == std::set<std::string>{"out"});
  fs::remove_all(root);
}

TEST_CASE("runs into one folder in place take turns: a commit waits for the folder's lock") {
  // Two runs at once into `-o .` each read the folder and moved their files in, leaving files of
  // both stands; a commit now holds the folder's flock while it reads and moves.
  const fs::path root = temp_dir();
  const fs::path dir = root / "out";
  write_set(dir.string(), "old", {"organs.csv", "plants.csv", "stand.ply"});
  const fs::path here = fs::current_path();
  fs::current_path(dir);
  const int held = ::open(".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);  // another run's lock
  REQUIRE(held >= 0);
  REQUIRE(::flock(held, LOCK_EX) == 0);
  std::atomic<bool> done{false};
  std::thread run([&] {
    write_set(".", "new", {"organs.csv", "plants.csv"});
    done = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  CHECK_FALSE(done.load());
  {
    std::ifstream in("organs.csv");
    CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == "old");  // nothing moved in yet
  }
  ::flock(held, LOCK_UN);
  ::close(held);
  run.join();
  CHECK(done.load());
  std::ifstream in("organs.csv");
  CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == "new");
  CHECK_FALSE(fs::exists("stand.ply"));  // the earlier set went whole
  fs::current_path(here);
  fs::remove_all(root);
}

TEST_CASE("temporary names carry their process; a dead one's are removed, a live one's kept") {
  CHECK(tag_is_dead(kDeadTag));
  CHECK(tag_is_dead("1073741000"));  // as earlier versions named them: a pid alone
  CHECK_FALSE(tag_is_dead(process_tag()));
  CHECK_FALSE(tag_is_dead("abc"));
  CHECK_FALSE(tag_is_dead(""));
  if (!process_tag().ends_with("-0"))  // the start time could be read: a reused pid is told apart
    CHECK(tag_is_dead(std::to_string(::getpid()) + "-1"));
  CHECK(is_dead_temporary("stand.glb.tmp-" + kDeadTag));
  CHECK(is_dead_temporary("stand.glb.tmp-mpi.rank3"));
  CHECK(is_dead_temporary("stand.glb.spill-rank0.tmp-" + kDeadTag));  // an MPI rank's, killed (mpi_files.cpp)
  CHECK_FALSE(is_dead_temporary("stand.glb.tmp-" + process_tag()));
  CHECK_FALSE(is_dead_temporary("notes.tmp-draft"));

  const fs::path root = temp_dir();
  put(root / ("summary.csv.tmp-" + kDeadTag), "debris");
  put(root / ("summary.csv.tmp-" + process_tag()), "");  // about to be reused by the file below
  put(root / "summary.csv.tmp-1", "pid 1 lives");
  {
    AtomicFile f((root / "summary.csv").string());
    f.write("whole");
    f.commit();
  }
  CHECK(names(root) == std::set<std::string>{"summary.csv", "summary.csv.tmp-1"});
  CHECK(slurp(root / "summary.csv") == "whole");
  {
    AtomicFile f((root / "summary.csv").string());
    f.write("torn");
  }  // not committed: the earlier file stays, the temporary goes
  CHECK(slurp(root / "summary.csv") == "whole");
  CHECK(names(root) == std::set<std::string>{"summary.csv", "summary.csv.tmp-1"});
  fs::remove_all(root);
}

TEST_CASE("a file name of up to 255 bytes is written; its temporary name is shortened") {
  const fs::path root = temp_dir();
  const std::string name = std::string(251, 'n') + ".csv";  // 255 bytes: ".tmp-PID-START" would pass
  const std::string stem = folder_ops::staging_stem(name);
  put(root / (stem + ".tmp-" + kDeadTag), "debris");
  {
    AtomicFile f((root / name).string());
    f.write("whole");
    f.commit();
  }
  CHECK(names(root) == std::set<std::string>{name});
  CHECK(slurp(root / name) == "whole");
  fs::remove_all(root);
}

TEST_CASE("registered paths are what a signal's clean-up removes") {
  const fs::path root = temp_dir();
  std::uint64_t a = 0, b = 0;
  {
    StagedFolder f((root / "x" / "out").string(), kStand);
    put(f.path("organs.csv"), "unfinished");
    a = register_run_path((root / "loose.tmp").string(), RunPath::file);
    put(root / "loose.tmp", "");
    b = register_run_path((root / "kept").string(), RunPath::file);
    unregister_run_path(b);
    put(root / "kept", "");
    const std::vector<std::string> removed = remove_run_paths();
    CHECK(removed.size() == 3);  // the file, the staging folder, the folder made above it
    CHECK(names(root) == std::set<std::string>{"kept"});
  }
  unregister_run_path(a);
  fs::remove_all(root);
}

TEST_CASE("number formatting checks every conversion") {
  std::string out;
  append_fixed(out, 123.25, 7);
  append_fixed(out, -0.0, 7);
  CHECK(out == "123.250");
  // A number past the field's 64 characters was appended from a buffer never written (1e57 in
  // stand.obj: 860 bytes of stack memory); it is an error now.
  CHECK_THROWS_WITH_AS(append_fixed(out, 1e57, 7),
                       doctest::Contains("cannot write the number 1.000000e+57 with 7 fixed decimals"),
                       std::range_error);
  CHECK(out == "123.250");
  append_number(out, 1e300);
  CHECK(out == "123.2501e+300");
}
