# MeshLab 2020.09 as Debian packages it, for building a filter plugin:
#   meshlab::common  IMPORTED target: libmeshlab-common.so, MeshLab's and
#                    vcglib's headers (as SYSTEM), Qt, GLEW, OpenGL, Eigen,
#                    MESHLAB_SCALAR=float (the ABI of Debian's build)
#   MESHLAB_LIB_DIR          folder of libmeshlab-common.so
#   MESHLAB_PLUGIN_DIR       the system plugin folder (${MESHLAB_LIB_DIR}/plugins)
#   MESHLAB_SERVER, MESHLAB_GUI  the installed binaries
#   MESHLAB_SOURCE_DIR       the extracted headers (src/common, vcglib)
#
# Debian ships no MeshLab headers: they come from Debian's source package of
# the installed version (fetch-meshlab-source.sh), extracted into the build
# folder (the primary cache) with the downloaded tarball kept in
# MESHNBV_MESHLAB_SOURCE_CACHE across build folders.

find_library(MESHLAB_COMMON_LIBRARY NAMES meshlab-common
  PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/meshlab /usr/lib/meshlab /usr/local/lib/meshlab
  NO_DEFAULT_PATH)
find_program(MESHLAB_SERVER meshlabserver)
find_program(MESHLAB_GUI meshlab)
if(NOT MESHLAB_COMMON_LIBRARY OR NOT MESHLAB_SERVER)
  message(FATAL_ERROR "MESHNBV_BUILD_MESHLAB=ON needs Debian's `meshlab` package "
                      "(libmeshlab-common.so, meshlabserver): run scripts/install-deps.sh")
endif()
get_filename_component(MESHLAB_LIB_DIR "${MESHLAB_COMMON_LIBRARY}" DIRECTORY)
set(MESHLAB_PLUGIN_DIR "${MESHLAB_LIB_DIR}/plugins")

if(DEFINED ENV{HOME} AND NOT "$ENV{HOME}" STREQUAL "")
  set(_meshlab_cache_default "$ENV{HOME}/.cache/meshnbv/meshlab-source")
else()
  set(_meshlab_cache_default "${CMAKE_BINARY_DIR}/meshlab-source-download")
endif()
set(MESHNBV_MESHLAB_SOURCE_CACHE "${_meshlab_cache_default}" CACHE PATH
    "Where the downloaded Debian source tarball of MeshLab is kept across build folders")
set(MESHLAB_SOURCE_DIR "${CMAKE_BINARY_DIR}/meshlab-source")

execute_process(
  COMMAND bash "${CMAKE_CURRENT_LIST_DIR}/fetch-meshlab-source.sh"
          "${MESHLAB_SOURCE_DIR}" "${MESHNBV_MESHLAB_SOURCE_CACHE}"
  RESULT_VARIABLE _meshlab_fetch_result)
if(NOT _meshlab_fetch_result EQUAL 0)
  message(FATAL_ERROR "could not get MeshLab's headers (see the messages above)")
endif()
file(READ "${MESHLAB_SOURCE_DIR}/.complete" MESHLAB_DEBIAN_VERSION)
string(STRIP "${MESHLAB_DEBIAN_VERSION}" MESHLAB_DEBIAN_VERSION)
message(STATUS "MeshLab ${MESHLAB_DEBIAN_VERSION}: headers in ${MESHLAB_SOURCE_DIR}, "
               "plugins in ${MESHLAB_PLUGIN_DIR}")

find_package(Qt5 5.12 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml)
find_package(GLEW REQUIRED)
find_package(OpenGL REQUIRED)

add_library(meshlab::common SHARED IMPORTED)
set_target_properties(meshlab::common PROPERTIES IMPORTED_LOCATION "${MESHLAB_COMMON_LIBRARY}")
# SYSTEM: vcglib's deprecation warnings (std::unary_function, ...) are not ours.
target_include_directories(meshlab::common SYSTEM INTERFACE
  "${MESHLAB_SOURCE_DIR}/src" "${MESHLAB_SOURCE_DIR}/vcglib")
target_compile_definitions(meshlab::common INTERFACE MESHLAB_SCALAR=float)
target_link_libraries(meshlab::common INTERFACE
  Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml GLEW::GLEW OpenGL::GL OpenGL::GLU Eigen3::Eigen)
