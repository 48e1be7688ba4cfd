#include "meshlab_test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace meshnbv::meshlab_test {

std::string quote(const std::string& path) {
  std::string out = "'";
  for (char c : path) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

Process run(const std::string& command) {
  Process r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run: " + command);
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

Process meshlabserver(const std::string& arguments) {
  // A display number per process (xvfb-run -a searches upwards from it):
  // ctest runs the tests in parallel processes.
  const int display = 200 + int(getpid() % 300);
  return run(std::string(XVFB_RUN) + " -a -n " + std::to_string(display) +
             " -s '-screen 0 1280x1024x24' bash " + quote(WITHOUT_TEMP_FOLDERS) + " " +
             quote((fs::path(WORK_DIR) / "readonly_tmp").string()) + " " + quote(MESHLAB_SERVER) +
             " " + arguments);
}

Process meshnbv_cli(const std::string& arguments) {
  return run(quote(MESHNBV_CLI) + " " + arguments);
}

std::string project_copy(const std::string& test_name) {
  const fs::path source = fs::path(WORK_DIR) / "project";
  if (!fs::exists(source / "ml.mlp"))
    throw std::runtime_error("fixture project missing: run the test meshlab/setup_project first (" +
                             source.string() + ")");
  const fs::path dir = fs::path(WORK_DIR) / "tests" / test_name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  fs::copy(source, dir, fs::copy_options::recursive);
  return dir.string();
}

std::string scratch_dir(const std::string& test_name) {
  const fs::path dir = fs::path(WORK_DIR) / "scratch" / (test_name + "." + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string script(const std::string& name) {
  return (fs::path(SCRIPTS_DIR) / (name + ".mlx")).string();
}

std::string edited_script(const std::string& name, const std::string& path,
                          const std::vector<std::pair<std::string, std::string>>& values) {
  std::ifstream in(script(name));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (const auto& [param, value] : values) {
    const std::string key = "name=\"" + param + "\" value=\"";
    const std::size_t at = text.find(key);
    if (at == std::string::npos) throw std::runtime_error("no parameter " + param + " in " + script(name));
    const std::size_t begin = at + key.size(), end = text.find('"', begin);
    text.replace(begin, end - begin, value);
  }
  std::ofstream(path) << text;
  return path;
}

}  // namespace meshnbv::meshlab_test
