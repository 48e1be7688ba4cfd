// Writes the box sample project: make_box_project <folder>.
#include <cstdio>

#include "box_scene.h"
#include "meshnbv/error.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_box_project <folder>\n");
    return 2;
  }
  try {
    meshnbv::test::write_box_project(argv[1]);
  } catch (const meshnbv::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
