// InputFile: what canopy reads of a user's file is bounded (a regular file, a size, a line).
#include "geometry/input_file.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

using namespace canopy;

namespace {
std::string write_temp(const std::string& text) {
  char name[] = "/tmp/canopy-input-XXXXXX";
  const int fd = mkstemp(name);
  REQUIRE(fd >= 0);
  close(fd);
  std::ofstream(name, std::ios::binary) << text;
  return name;
}
}  // namespace

TEST_CASE(
    "lines as written: the last without a line break, a Windows line end's CR dropped, empty lines counted") {
  const std::string f = write_temp("a,b\r\n\nlast");
  InputFile in(f, "test file", 100);
  std::string line;
  REQUIRE(in.next_line(line));
  CHECK(line == "a,b");
  REQUIRE(in.next_line(line));
  CHECK(line == "");
  REQUIRE(in.next_line(line));
  CHECK(line == "last");
  CHECK(in.line_number() == 3);
  CHECK_FALSE(in.next_line(line));
  std::remove(f.c_str());
}

TEST_CASE("a long line across many reads, and one longer than the bound") {
  const std::string longline(200000, 'x');
  const std::string f = write_temp("short\n" + longline + "\nafter\n");
  {
    InputFile in(f, "test file", 1 << 20);
    std::string line;
    REQUIRE(in.next_line(line));
    REQUIRE(in.next_line(line, 300000));
    CHECK(line == longline);
    REQUIRE(in.next_line(line));
    CHECK(line == "after");
  }
  InputFile in(f, "test file", 1 << 20);
  std::string line;
  REQUIRE(in.next_line(line));
  CHECK_THROWS_WITH_AS(in.next_line(line),
                       (f + ":2: a line of the test file is longer than the 64 KiB canopy reads").c_str(),
                       InputRefused);
  std::remove(f.c_str());
}

TEST_CASE(
    "lines ended by a carriage return alone are refused, short or long, with or without a last line end") {
  const std::string mac =
      "the test file's lines end with a carriage return alone (an old Mac format); save the "
      "file with \\n or \\r\\n line ends";
  for (const std::string text : {"a,b\rc,d\r", "a,b\rc,d\r\n", "ok\r\na,b\rc,d"}) {
    CAPTURE(text);
    const std::string f = write_temp(text);
    InputFile in(f, "test file", 100);
    std::string line;
    const bool first_ok = text.starts_with("ok");
    if (first_ok) REQUIRE(in.next_line(line));
    CHECK_THROWS_WITH_AS(in.next_line(line), (f + (first_ok ? ":2: " : ":1: ") + mac).c_str(), InputRefused);
    std::remove(f.c_str());
  }
  const std::string f = write_temp("a,b\r" + std::string(70000, 'x') + "\r");
  InputFile in(f, "test file", 1 << 20);
  std::string line;
  CHECK_THROWS_WITH_AS(in.next_line(line), (f + ":1: " + mac).c_str(), InputRefused);
  std::remove(f.c_str());
}

TEST_CASE("a NUL byte in a line is refused with its place (it cut the messages quoting the line)") {
  const std::string f = write_temp(std::string("a,b\nc,0.", 8) + std::string(1, '\0') + "5\n");
  InputFile in(f, "test file", 100);
  std::string line;
  REQUIRE(in.next_line(line));
  CHECK_THROWS_WITH_AS(
      in.next_line(line),
      (f + ":2: column 5: a NUL byte, which no text file holds (the test file is binary or damaged)").c_str(),
      InputRefused);
  std::remove(f.c_str());
}

TEST_CASE("files larger than the limit, by their size or by what is read") {
  const std::string f = write_temp(std::string(2000, 'y'));
  CHECK_THROWS_WITH_AS(InputFile(f, "test file", 1024),
                       (f + ": the test file is larger than the 1 KiB canopy reads (2000 bytes)").c_str(),
                       InputRefused);
  CHECK(read_input_file(f, "test file", 2000).size() == 2000);
  std::remove(f.c_str());
  // A file under /proc says its size is 0; what is read counts.
  CHECK_THROWS_WITH_AS(read_input_file("/proc/self/maps", "test file", 16),
                       "/proc/self/maps: the test file is larger than the 16 bytes canopy reads",
                       InputRefused);
}

TEST_CASE("folders, devices and pipes are refused without waiting or reading") {
  CHECK_THROWS_WITH_AS(InputFile("/tmp", "test file", 1024), "/tmp: the test file is a folder, not a file",
                       InputRefused);
  CHECK_THROWS_WITH_AS(InputFile("/dev/zero", "test file", 1024),
                       "/dev/zero: the test file is not a regular file (a device, pipe or socket)",
                       InputRefused);
  char fifo[] = "/tmp/canopy-fifo-XXXXXX";
  REQUIRE(mkdtemp(fifo));
  const std::string path = std::string(fifo) + "/pipe";
  REQUIRE(mkfifo(path.c_str(), 0600) == 0);
  // Opening a FIFO for reading waits for a writer unless told not to.
  CHECK_THROWS_AS(InputFile(path, "test file", 1024), InputRefused);
  std::remove(path.c_str());
  rmdir(fifo);
  CHECK_THROWS_WITH_AS(InputFile("/tmp/canopy-no-such-input", "test file", 1024),
                       "/tmp/canopy-no-such-input: cannot open the test file", FileNotFound);
}
