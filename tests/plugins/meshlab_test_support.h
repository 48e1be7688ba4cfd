// Running meshlabserver and the meshnbv CLI from the tests.
#pragma once

#include <string>
#include <vector>

namespace meshnbv::meshlab_test {

struct Process {
  int status = -1;     // exit status (128 + signal when killed, as the shell reports it)
  std::string output;  // stdout and stderr
};

// Runs `command` through /bin/sh, capturing both streams.
Process run(const std::string& command);
// meshlabserver of the build's private prefix, under xvfb-run, with no
// writable temporary folder (TMPDIR, HOME and, where a mount namespace is
// allowed, /tmp read-only: tests/support/without_temp_folders.sh).
Process meshlabserver(const std::string& arguments);
// The meshnbv command line tool.
Process meshnbv_cli(const std::string& arguments);

// A fresh copy of the fixture project for one test: WORK/tests/<name>/.
std::string project_copy(const std::string& test_name);
// A fresh, empty folder for one test in the build folder (not the system's
// temporary folder): WORK/scratch/<name>.<pid>.
std::string scratch_dir(const std::string& test_name);
// A sample script (sample_projects/meshlab/<name>.mlx).
std::string script(const std::string& name);
// `script(name)` with parameter values replaced ({name, value}), written to `path`.
std::string edited_script(const std::string& name, const std::string& path,
                          const std::vector<std::pair<std::string, std::string>>& values);

std::string quote(const std::string& path);

}  // namespace meshnbv::meshlab_test
