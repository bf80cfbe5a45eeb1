// Files that steer a machine live only in folders nobody else can change
// (gcode/serial/link/private_path.hpp): the folder of a path, a port's file
// name, and a folder others may write to refused.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <string>

#include "gcode/serial/link/private_path.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

TEST_CASE("private path: the folder of a path and a port's file name", "[serial][private_path]") {
  CHECK(folder_of("/dev/ttyACM0") == "/dev");
  CHECK(folder_of("print.journal") == ".");
  CHECK(folder_of("/print.journal") == "/");
  CHECK(port_file_name("/dev/ttyACM0") == "ttyACM0");
  CHECK(port_file_name("virtual:time-scale=20") == "virtual");
  CHECK(port_file_name("") == "port");
}

TEST_CASE("private path: a folder others may write to is refused, a private one taken", "[serial][private_path]") {
  const std::string dir = gctest::temp_dir() + "/private_path";
  make_private_folder(dir + "/x");
  CHECK(folder_problem(dir, "journal").empty());
  REQUIRE(::chmod(dir.c_str(), 0777) == 0);
  const std::string problem = folder_problem(dir, "journal");
  CHECK(problem.find("journal refused") == 0);
  REQUIRE(::chmod(dir.c_str(), 01777) == 0);  // sticky, as /tmp
  CHECK(folder_problem(dir, "journal").empty());
  ::chmod(dir.c_str(), 0700);
  CHECK(folder_problem(dir + "/not-yet", "journal").empty());  // made 0700 when needed
}
