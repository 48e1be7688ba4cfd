#include "meshnbv/io/file_util.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <fcntl.h>
#include <unistd.h>

#include "meshnbv/error.h"

namespace fs = std::filesystem;

namespace meshnbv::io {

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("file not found", path);
  if (fs::is_directory(path, ec)) throw Error("is a folder, expected a file", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(std::string("cannot open: ") + std::strerror(errno), path);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error("read error", path);
  return ss.str();
}

std::uintmax_t file_size(const std::string& path) {
  std::error_code ec;
  auto size = fs::file_size(path, ec);
  if (ec) throw Error("cannot stat: " + ec.message(), path);
  return size;
}

bool is_file(const std::filesystem::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string extension_lower(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

namespace {

void refuse_existing(const std::string& path, bool overwrite) {
  std::error_code ec;
  if (!overwrite && fs::exists(path, ec))
    throw Error("output exists; pass --overwrite to replace it", path);
}

// Throws unless a file can be created in the existing folder `dir`: tried
// with a probe file (access() says yes to root on a mode-0555 folder and on
// /proc, where creating files fails).
void probe_folder(const fs::path& dir, const std::string& output) {
  static std::atomic<unsigned> counter{0};
  const fs::path probe = dir / (".meshnbv_write_probe_" + std::to_string(::getpid()) + "_" +
                                std::to_string(counter++));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int err = errno;
    throw Error("cannot create files in folder '" + dir.string() + "': " + std::strerror(err),
                output);
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

// The folder `dir` (empty = the current one) exists and is writable, or the
// nearest existing ancestor is, so that it can be created.
void check_folder_writable(fs::path dir, const std::string& output) {
  if (dir.empty()) dir = ".";
  std::error_code ec;
  fs::path existing = dir;
  while (true) {
    const fs::file_status st = fs::status(existing, ec);
    if (st.type() == fs::file_type::directory) break;
    if (fs::exists(st))
      throw Error("cannot write under '" + existing.string() + "': it is a file, not a folder",
                  output);
    if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory)
      throw Error("cannot write under '" + existing.string() + "': " + ec.message(), output);
    const fs::path parent = existing.parent_path();
    if (parent.empty() || parent == existing) {
      existing = existing.is_absolute() ? existing.root_path() : fs::path(".");
      break;
    }
    existing = parent;
  }
  probe_folder(existing, output);
}

}  // namespace

void check_can_write(const std::string& path, bool overwrite) {
  if (path.empty()) throw Error("empty output file name");
  const fs::path target(path);
  if (!target.has_filename()) throw Error("names a folder, expected a file", path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw Error("is a folder, expected a file", path);
  refuse_existing(path, overwrite);
  check_folder_writable(target.parent_path(), path);
}

void check_can_write_folder(const std::string& path) {
  if (path.empty()) throw Error("empty output folder name");
  const fs::path dir(path);
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st) && st.type() != fs::file_type::directory)
    throw Error("is a file, expected a folder", path);
  check_folder_writable(dir, path);
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                      bool overwrite, bool binary) {
  refuse_existing(path, overwrite);
  fs::path target(path);
  fs::path folder = target.parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::exists(folder, ec)) {
    fs::create_directories(folder, ec);
    if (ec) throw Error("cannot create folder: " + ec.message(), folder.string());
  }
  static std::atomic<unsigned> counter{0};
  fs::path tmp = target;
  tmp += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::out : std::ios::out);
      if (!out) throw Error(std::string("cannot write: ") + std::strerror(errno), path);
      write(out);
      out.flush();
      if (!out) throw Error("write failed (disk full?)", path);
    }
    fs::rename(tmp, target, ec);
    if (ec) throw Error("cannot move the finished file into place: " + ec.message(), path);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

std::string relative_to(const std::string& path, const std::string& base) {
  if (path.empty()) return path;
  fs::path abs_path = fs::absolute(path).lexically_normal();
  fs::path abs_base = fs::absolute(base.empty() ? "." : base).lexically_normal();
  fs::path rel = abs_path.lexically_relative(abs_base);
  if (rel.empty()) return abs_path.string();
  return rel.generic_string();
}

std::string resolve(const std::string& path, const std::string& base) {
  if (path.empty()) return path;
  fs::path p(path);
  if (p.is_absolute() || base.empty()) return p.lexically_normal().string();
  return (fs::path(base) / p).lexically_normal().string();
}

TextTokens::TextTokens(std::string text, std::string file)
    : text_(std::move(text)), file_(std::move(file)) {}

bool TextTokens::next_line(std::vector<std::string>* tokens) {
  tokens->clear();
  while (pos_ < text_.size()) {
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    ++line_;
    std::size_t i = pos_;
    pos_ = end + 1;
    while (i < end) {
      while (i < end && std::isspace(static_cast<unsigned char>(text_[i]))) ++i;
      std::size_t start = i;
      while (i < end && !std::isspace(static_cast<unsigned char>(text_[i]))) ++i;
      if (i > start) tokens->emplace_back(text_, start, i - start);
    }
    if (!tokens->empty()) return true;
  }
  return false;
}

double parse_double(const std::string& token, const std::string& file, long line,
                    const std::string& what) {
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0')
    throw Error("expected a number for " + what + ", got '" + token + "'", file, line);
  if (!std::isfinite(value) || errno == ERANGE)
    throw Error(what + " is not a finite number ('" + token + "')", file, line);
  return value;
}

long long parse_int(const std::string& token, const std::string& file, long line,
                    const std::string& what) {
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  long long value = std::strtoll(begin, &end, 10);
  if (end == begin || *end != '\0' || errno == ERANGE)
    throw Error("expected an integer for " + what + ", got '" + token + "'", file, line);
  return value;
}

}  // namespace meshnbv::io

namespace meshnbv::io {
namespace {

bool has_image_extension(const std::string& path) {
  static const char* kExtensions[] = {".jpg", ".jpeg", ".png", ".tif", ".tiff",
                                      ".pgm", ".ppm",  ".bmp"};
  const std::string ext = extension_lower(path);
  for (const char* e : kExtensions)
    if (ext == e) return true;
  return false;
}

std::string first_match(const std::vector<std::pair<std::string, std::string>>& sorted,
                        const std::string& key) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(key, std::string()));
  return it != sorted.end() && it->first == key ? it->second : std::string();
}

}  // namespace

ImageIndex::ImageIndex(const std::string& folder) : folder_(folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw Error("image folder not found (or not a folder)", folder);
  fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec);
  std::size_t seen = 0;
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (++seen > kMaxFiles) break;
    if (!it->is_regular_file(ec)) continue;
    const fs::path& p = it->path();
    if (!has_image_extension(p.string())) continue;
    by_name_.emplace_back(p.filename().string(), p.string());
    by_stem_.emplace_back(p.stem().string(), p.string());
  }
  std::sort(by_name_.begin(), by_name_.end());
  std::sort(by_stem_.begin(), by_stem_.end());
}

std::string ImageIndex::find(const std::string& name) const {
  // Windows paths from another machine: the file name follows the last \ or /.
  const std::size_t slash = name.find_last_of("/\\");
  const std::string file = slash == std::string::npos ? name : name.substr(slash + 1);
  std::string found = first_match(by_name_, file);
  if (found.empty() && !has_image_extension(file)) found = first_match(by_stem_, file);
  return found;
}

}  // namespace meshnbv::io
