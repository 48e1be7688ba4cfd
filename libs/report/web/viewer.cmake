# The report's 3-D viewer (docs/user-guide.md, "The 3-D view"): three.js and
# our viewer code (src/*.js), bundled by esbuild into one classic script
# (IIFE: module scripts do not load from file://), embedded into
# meshnbv_report as bytes, so that `meshnbv` alone writes a complete report.
# npm ci and the bundle run at build time in the build tree, again only when
# package.json, package-lock.json or a source changes. Included from
# libs/CMakeLists.txt after meshnbv_report is defined.
find_program(MESHNBV_NPM npm)
find_program(MESHNBV_NODE NAMES node nodejs)
if(NOT MESHNBV_NPM OR NOT MESHNBV_NODE)
  message(FATAL_ERROR "npm/node not found: the report's 3-D viewer is bundled with npm at build time; "
                      "install Debian's nodejs and npm (scripts/install-deps.sh)")
endif()

set(web_source ${CMAKE_CURRENT_LIST_DIR})
set(web_build ${CMAKE_CURRENT_BINARY_DIR}/report_web)
file(MAKE_DIRECTORY ${web_build})
file(GLOB viewer_sources CONFIGURE_DEPENDS ${web_source}/src/*.js)

# Dependencies exactly as locked (three, esbuild, and playwright-core for the
# browser tests: tests/report/).
add_custom_command(OUTPUT ${web_build}/npm_ci.stamp
  COMMAND ${CMAKE_COMMAND} -E copy_if_different ${web_source}/package.json ${web_source}/package-lock.json
          ${web_build}
  COMMAND ${MESHNBV_NPM} ci --no-audit --no-fund --loglevel=error
  COMMAND ${CMAKE_COMMAND} -E touch ${web_build}/npm_ci.stamp
  WORKING_DIRECTORY ${web_build}
  DEPENDS ${web_source}/package.json ${web_source}/package-lock.json
  COMMENT "npm ci: the report viewer's dependencies"
  VERBATIM)

# The sources stay in the source tree; NODE_PATH lets esbuild find the
# packages installed in the build tree.
add_custom_command(OUTPUT ${web_build}/meshnbv_viewer.js
  COMMAND ${CMAKE_COMMAND} -E env NODE_PATH=${web_build}/node_modules
          ${web_build}/node_modules/.bin/esbuild ${web_source}/src/viewer.js
          --bundle --format=iife --minify --target=es2019 --log-level=warning
          --outfile=${web_build}/meshnbv_viewer.js
  DEPENDS ${web_build}/npm_ci.stamp ${viewer_sources}
  COMMENT "esbuild: the report's 3-D viewer"
  VERBATIM)

add_custom_command(OUTPUT ${web_build}/viewer_bundle.cpp
  COMMAND ${MESHNBV_NODE} ${web_source}/embed.mjs ${web_build}/meshnbv_viewer.js ${web_build}/viewer_bundle.cpp
  DEPENDS ${web_build}/meshnbv_viewer.js ${web_source}/embed.mjs
  COMMENT "Embedding the report's 3-D viewer"
  VERBATIM)
target_sources(meshnbv_report PRIVATE ${web_build}/viewer_bundle.cpp)

# For the browser tests (playwright-core) and the bench.
set(MESHNBV_WEB_NODE_MODULES ${web_build}/node_modules CACHE INTERNAL "node_modules of the report viewer")
