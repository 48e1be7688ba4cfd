#include "meshnbv/image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "meshnbv/error.h"

namespace meshnbv {

Image::Image(int width, int height, int channels, int bits)
    : width_(width), height_(height), channels_(channels), bits_(bits) {
  if (width <= 0 || height <= 0 || (channels != 1 && channels != 3) || (bits != 8 && bits != 16))
    throw Error("invalid image size " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                std::to_string(channels) + " at " + std::to_string(bits) + " bits");
  const std::size_t n = std::size_t(width) * height * channels;
  if (bits == 16)
    data16_.assign(n, 0);
  else
    data_.assign(n, 0);
}

bool is_jpeg_file(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  unsigned char head[3] = {0, 0, 0};
  const std::size_t got = std::fread(head, 1, 3, f);
  std::fclose(f);
  return got == 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF;
}

Image Image::load(const std::string& path, ImageOrientation orientation, int reduction) {
  if (reduction != 1 && reduction != 2 && reduction != 4 && reduction != 8)
    throw Error("image reduction must be 1, 2, 4 or 8, not " + std::to_string(reduction), path);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("image file not found", path);
  // Any depth, grey or colour as stored (colour without its alpha); the
  // EXIF orientation applied or not as asked.
  int flags = cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR;
  if (orientation == ImageOrientation::stored) flags |= cv::IMREAD_IGNORE_ORIENTATION;
  // OpenCV hands the reduction to libjpeg's DCT scaling for a JPEG; for any
  // other format it would decode in full and resize, which is no saving and
  // another filter: those are decoded at full resolution.
  if (reduction > 1 && !is_jpeg_file(path)) reduction = 1;
  if (reduction == 2) flags |= cv::IMREAD_REDUCED_GRAYSCALE_2;
  if (reduction == 4) flags |= cv::IMREAD_REDUCED_GRAYSCALE_4;
  if (reduction == 8) flags |= cv::IMREAD_REDUCED_GRAYSCALE_8;
  cv::Mat mat;
  try {
    mat = cv::imread(path, flags);
  } catch (const cv::Exception& e) {
    throw Error(std::string("image does not decode: ") + e.what(), path);
  }
  if (mat.empty()) throw Error("image does not decode (unknown or corrupt format)", path);
  int bits = 8;
  if (mat.depth() == CV_16U) {
    bits = 16;
  } else if (mat.depth() != CV_8U) {
    // Floating-point (and other) images: to 16 bits, [0, 1] -> [0, 65535]
    // for floats, saturated.
    const double scale = (mat.depth() == CV_32F || mat.depth() == CV_64F) ? 65535.0 : 1.0;
    cv::Mat converted;
    mat.convertTo(converted, CV_16U, scale);
    mat = converted;
    bits = 16;
  }
  cv::Mat out;
  switch (mat.channels()) {
    case 1:
      out = mat;
      break;
    case 2:
      cv::extractChannel(mat, out, 0);
      break;  // grey + alpha
    case 3:
      cv::cvtColor(mat, out, cv::COLOR_BGR2RGB);
      break;
    case 4:
      cv::cvtColor(mat, out, cv::COLOR_BGRA2RGB);
      break;
    default:
      throw Error("unsupported channel count " + std::to_string(mat.channels()), path);
  }
  Image image(out.cols, out.rows, out.channels(), bits);
  const std::size_t row_bytes = std::size_t(out.cols) * out.channels() * (bits / 8);
  for (int y = 0; y < out.rows; ++y) {
    void* dst = bits == 16 ? static_cast<void*>(image.pixel16(0, y)) : static_cast<void*>(image.pixel(0, y));
    std::memcpy(dst, out.ptr(y), row_bytes);
  }
  image.reduction_ = reduction;
  return image;
}

Image Image::to_8bit() const {
  if (bits_ == 8 || empty()) return *this;
  Image out(width_, height_, channels_, 8);
  for (std::size_t i = 0; i < data16_.size(); ++i)
    out.data_[i] = static_cast<std::uint8_t>((unsigned(data16_[i]) + 128u) / 257u);
  return out;
}

void Image::save(const std::string& path) const {
  if (empty()) throw Error("cannot save an empty image", path);
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool keeps_16 = ext == ".png" || ext == ".tif" || ext == ".tiff";
  if (bits_ == 16 && !keeps_16) {
    to_8bit().save(path);
    return;
  }
  const int depth = bits_ == 16 ? CV_16U : CV_8U;
  cv::Mat mat(height_, width_, CV_MAKETYPE(depth, channels_), const_cast<std::uint8_t*>(data()));
  cv::Mat out;
  if (channels_ == 3)
    cv::cvtColor(mat, out, cv::COLOR_RGB2BGR);
  else
    out = mat;
  bool ok = false;
  try {
    ok = cv::imwrite(path, out);
  } catch (const cv::Exception& e) {
    throw Error(std::string("cannot write image: ") + e.what(), path);
  }
  if (!ok) throw Error("cannot write image (unknown extension or unwritable folder)", path);
}

namespace {
constexpr float kInv255 = 1.0f / 255.0f;
constexpr float kInv65535 = 1.0f / 65535.0f;

template <typename T>
inline float luma(const T* p, int channels, float inv) {
  if (channels == 1) return p[0] * inv;
  return (0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2]) * inv;
}

// Integer cell and weights for bilinear sampling on [0, n-1]; false outside.
inline bool cell(double x, int n, int* x0, int* x1, float* w) {
  if (!(x >= 0.0 && x <= n - 1.0)) return false;  // also rejects NaN
  int i = static_cast<int>(x);
  if (i >= n - 1) i = n - 1;
  *x0 = i;
  *x1 = i + 1 < n ? i + 1 : i;
  *w = static_cast<float>(x - i);
  return true;
}
}  // namespace

float Image::value(int x, int y, int c) const {
  const int k = channels_ == 1 ? 0 : c;
  return bits_ == 16 ? pixel16(x, y)[k] * kInv65535 : pixel(x, y)[k] * kInv255;
}

float Image::luminance(int x, int y) const {
  return bits_ == 16 ? luma(pixel16(x, y), channels_, kInv65535) : luma(pixel(x, y), channels_, kInv255);
}

bool Image::sample_luminance(double x, double y, float* out) const {
  int x0, x1, y0, y1;
  float wx, wy;
  if (!cell(x, width_, &x0, &x1, &wx) || !cell(y, height_, &y0, &y1, &wy)) return false;
  const float a = luminance(x0, y0), b = luminance(x1, y0);
  const float c = luminance(x0, y1), d = luminance(x1, y1);
  *out = (1 - wy) * ((1 - wx) * a + wx * b) + wy * ((1 - wx) * c + wx * d);
  return true;
}

namespace {
template <typename T>
void bilinear_rgb(const T* a, const T* b, const T* c, const T* d, int channels, float wx, float wy, float inv,
                  float out[3]) {
  for (int ch = 0; ch < 3; ++ch) {
    const int k = channels == 1 ? 0 : ch;
    out[ch] = ((1 - wy) * ((1 - wx) * a[k] + wx * b[k]) + wy * ((1 - wx) * c[k] + wx * d[k])) * inv;
  }
}
}  // namespace

bool Image::sample_rgb(double x, double y, float out[3]) const {
  int x0, x1, y0, y1;
  float wx, wy;
  if (!cell(x, width_, &x0, &x1, &wx) || !cell(y, height_, &y0, &y1, &wy)) return false;
  if (bits_ == 16)
    bilinear_rgb(pixel16(x0, y0), pixel16(x1, y0), pixel16(x0, y1), pixel16(x1, y1), channels_, wx, wy,
                 kInv65535, out);
  else
    bilinear_rgb(pixel(x0, y0), pixel(x1, y0), pixel(x0, y1), pixel(x1, y1), channels_, wx, wy, kInv255, out);
  return true;
}

namespace {

// Row y of `image` (samples of type T, `channels` interleaved) into `out`:
// luminance (out_channels 1) or each colour channel (3), with the same
// arithmetic as Image::luminance and Image::value, so the planes equal the
// per-pixel reads bit for bit. One loop per row without branches, which the
// compiler vectorises.
template <typename T, int channels, int out_channels>
void convert_row(const T* p, int width, float inv, float* out) {
  for (int x = 0; x < width; ++x, p += channels) {
    if constexpr (out_channels == 1) {
      if constexpr (channels == 1)
        out[x] = p[0] * inv;
      else
        out[x] = (0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2]) * inv;
    } else {
      for (int c = 0; c < 3; ++c) out[3 * x + c] = p[channels == 1 ? 0 : c] * inv;
    }
  }
}

template <int out_channels>
void convert_rows(const Image& image, float* out) {
  const int w = image.width(), channels = image.channels();
  tbb::parallel_for(tbb::blocked_range<int>(0, image.height(), 16), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y) {
      float* row = out + std::size_t(y) * w * out_channels;
      if (image.bits() == 16) {
        const std::uint16_t* p = image.pixel16(0, y);
        if (channels == 1)
          convert_row<std::uint16_t, 1, out_channels>(p, w, kInv65535, row);
        else
          convert_row<std::uint16_t, 3, out_channels>(p, w, kInv65535, row);
      } else {
        const std::uint8_t* p = image.pixel(0, y);
        if (channels == 1)
          convert_row<std::uint8_t, 1, out_channels>(p, w, kInv255, row);
        else
          convert_row<std::uint8_t, 3, out_channels>(p, w, kInv255, row);
      }
    }
  });
}

}  // namespace

FloatImage FloatImage::luminance_of(const Image& image) {
  FloatImage out;
  out.width_ = image.width();
  out.height_ = image.height();
  out.channels_ = 1;
  out.data_.resize(std::size_t(out.width_) * out.height_);
  if (!image.empty()) convert_rows<1>(image, out.data_.data());
  return out;
}

FloatImage FloatImage::rgb_of(const Image& image) {
  FloatImage out;
  out.width_ = image.width();
  out.height_ = image.height();
  out.channels_ = 3;
  out.data_.resize(std::size_t(out.width_) * out.height_ * 3);
  if (!image.empty()) convert_rows<3>(image, out.data_.data());
  return out;
}

bool FloatImage::sample(double x, double y, float* out) const {
  int x0, x1, y0, y1;
  float wx, wy;
  if (!cell(x, width_, &x0, &x1, &wx) || !cell(y, height_, &y0, &y1, &wy)) return false;
  const float* r0 = &data_[std::size_t(y0) * width_ * channels_];
  const float* r1 = &data_[std::size_t(y1) * width_ * channels_];
  for (int c = 0; c < channels_; ++c) {
    const float a = r0[x0 * channels_ + c], b = r0[x1 * channels_ + c];
    const float d0 = r1[x0 * channels_ + c], d1 = r1[x1 * channels_ + c];
    out[c] = (1 - wy) * ((1 - wx) * a + wx * b) + wy * ((1 - wx) * d0 + wx * d1);
  }
  return true;
}

ImageCache::ImageCache(std::size_t max_bytes) : max_bytes_(max_bytes) {}

std::shared_ptr<const Image> ImageCache::get(const std::string& path, ImageOrientation orientation,
                                             int reduction) {
  // The key: the path, and for the EXIF orientation and a reduction
  // suffixes no path holds.
  std::string key = orientation == ImageOrientation::exif ? path + std::string("\0exif", 5) : path;
  if (reduction != 1) key += std::string("\0r", 2) + std::to_string(reduction);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = entries_.find(key);
    if (it != entries_.end()) {
      lru_.splice(lru_.begin(), lru_, it->second.lru_position);
      return it->second.image;
    }
  }
  // Decode outside the lock so that threads load different images in parallel.
  auto image = std::make_shared<const Image>(Image::load(path, orientation, reduction));
  std::lock_guard<std::mutex> lock(mutex_);
  ++loads_;
  auto it = entries_.find(key);
  if (it != entries_.end()) return it->second.image;  // another thread won the race
  lru_.push_front(key);
  entries_[key] = Entry{image, lru_.begin()};
  bytes_ += image->bytes();
  evict_locked();
  return image;
}

void ImageCache::evict_locked() {
  // Keep at least the newest image even when it alone exceeds the budget.
  while (bytes_ > max_bytes_ && lru_.size() > 1) {
    const std::string& victim = lru_.back();
    auto it = entries_.find(victim);
    bytes_ -= it->second.image->bytes();
    entries_.erase(it);
    lru_.pop_back();
  }
}

void ImageCache::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.clear();
  lru_.clear();
  bytes_ = 0;
}

std::size_t ImageCache::bytes_held() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

std::size_t ImageCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

std::size_t ImageCache::loads() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return loads_;
}

}  // namespace meshnbv
