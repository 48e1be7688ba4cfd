// Small helpers shared by the readers and writers.
#pragma once

#include <cstdint>
#include <functional>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace meshnbv::io {

// Whole file as bytes; throws Error if missing or unreadable.
std::string read_file(const std::string& path);
std::uintmax_t file_size(const std::string& path);
// True when `path` is a regular file (or a link to one); false when it is
// missing, a folder, or cannot be examined. Never throws.
bool is_file(const std::filesystem::path& path);
// Lower-case extension with the dot (".ply"); empty if none.
std::string extension_lower(const std::string& path);

// Writes through a temporary file in the same folder, renamed over `path`
// only when `write` returned normally, so a failure never leaves a
// half-written file. Throws Error if `path` exists and !overwrite.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                      bool overwrite = true, bool binary = false);

// Checks, before anything is computed, that `path` can be written as a
// file: it is not a folder, it does not exist unless `overwrite`, and its
// folder is a writable folder or can be created (the nearest existing
// ancestor is a folder that a file can be created in; tried with a probe
// file, so that read-only mounts and root's view of /proc count too).
// Throws Error naming the output and the reason otherwise.
void check_can_write(const std::string& path, bool overwrite);
// The same for an output folder: `path` is a folder that a file can be
// created in, or can be created. Whether its contents may be replaced is
// the caller's business.
void check_can_write_folder(const std::string& path);

// `path` relative to folder `base` when possible (lexically), else absolute.
std::string relative_to(const std::string& path, const std::string& base);
// Resolve `path` against folder `base` when it is relative.
std::string resolve(const std::string& path, const std::string& base);

// Whitespace tokenizer with line tracking for the text formats.
class TextTokens {
 public:
  TextTokens(std::string text, std::string file);
  bool next_line(std::vector<std::string>* tokens);  // skips blank lines
  long line() const { return line_; }
  const std::string& file() const { return file_; }

 private:
  std::string text_;
  std::string file_;
  std::size_t pos_ = 0;
  long line_ = 0;
};

// Strict numeric parsing: the whole token must be a finite number.
double parse_double(const std::string& token, const std::string& file, long line,
                    const std::string& what);
long long parse_int(const std::string& token, const std::string& file, long line,
                    const std::string& what);

}  // namespace meshnbv::io

namespace meshnbv::io {

// Image files under a folder, searched recursively by name: for projects
// whose image paths were written on another machine (a project moved
// between machines, or a format that stores only labels). Extensions
// searched: .jpg .jpeg .png .tif .tiff .pgm .ppm .bmp (any case).
class ImageIndex {
 public:
  ImageIndex() = default;
  // Walks `folder` once (at most kMaxFiles files; symlinked folders are not
  // followed). Throws Error when `folder` is not a folder.
  explicit ImageIndex(const std::string& folder);
  static constexpr std::size_t kMaxFiles = 1000000;

  // The file whose name equals the file name of `name` (the folders of
  // `name` are ignored), else, when `name` has no image extension, the file
  // whose stem is `name` (Metashape labels). The first in path order when
  // several match; "" when none does.
  std::string find(const std::string& name) const;
  bool empty() const { return by_name_.empty(); }
  const std::string& folder() const { return folder_; }

 private:
  std::string folder_;
  std::vector<std::pair<std::string, std::string>> by_name_;  // (file name, path), sorted
  std::vector<std::pair<std::string, std::string>> by_stem_;  // (stem, path), sorted
};

}  // namespace meshnbv::io
