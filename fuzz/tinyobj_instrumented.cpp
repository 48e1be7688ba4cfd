// Fuzz build only: tinyobjloader's parser compiled here, with coverage and
// sanitizer instrumentation. Debian ships it as a prebuilt shared library,
// which libFuzzer cannot see into; the definitions in this executable take
// precedence over the library's at run time (the executable comes first in
// the dynamic linker's search), so read_obj runs this copy. Same header, same
// version (float build, like tinyobjloader::tinyobjloader).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
