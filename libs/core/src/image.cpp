#include "meshnbv/image.h"

#include <cmath>
#include <cstring>
#include <filesystem>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "meshnbv/error.h"

namespace meshnbv {

Image::Image(int width, int height, int channels)
    : width_(width), height_(height), channels_(channels) {
  if (width <= 0 || height <= 0 || (channels != 1 && channels != 3))
    throw Error("invalid image size " + std::to_string(width) + "x" + std::to_string(height) +
                "x" + std::to_string(channels));
  data_.assign(std::size_t(width) * height * channels, 0);
}

Image Image::load(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("image file not found", path);
  cv::Mat mat;
  try {
    mat = cv::imread(path, cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH);
  } catch (const cv::Exception& e) {
    throw Error(std::string("image does not decode: ") + e.what(), path);
  }
  if (mat.empty()) throw Error("image does not decode (unknown or corrupt format)", path);
  if (mat.depth() != CV_8U) {
    // 16-bit (or float) images: scale to 8 bits by the type's range.
    double scale = mat.depth() == CV_16U ? 1.0 / 257.0 : (mat.depth() == CV_32F ? 255.0 : 1.0);
    cv::Mat converted;
    mat.convertTo(converted, CV_8U, scale);
    mat = converted;
  }
  cv::Mat out;
  switch (mat.channels()) {
    case 1: out = mat; break;
    case 3: cv::cvtColor(mat, out, cv::COLOR_BGR2RGB); break;
    case 4: cv::cvtColor(mat, out, cv::COLOR_BGRA2RGB); break;
    default:
      throw Error("unsupported channel count " + std::to_string(mat.channels()), path);
  }
  Image image(out.cols, out.rows, out.channels());
  const std::size_t row_bytes = std::size_t(out.cols) * out.channels();
  for (int y = 0; y < out.rows; ++y) std::memcpy(image.pixel(0, y), out.ptr(y), row_bytes);
  return image;
}

void Image::save(const std::string& path) const {
  if (empty()) throw Error("cannot save an empty image", path);
  cv::Mat mat(height_, width_, channels_ == 1 ? CV_8UC1 : CV_8UC3,
              const_cast<std::uint8_t*>(data_.data()));
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

inline float luma(const std::uint8_t* p, int channels) {
  if (channels == 1) return p[0] * kInv255;
  return (0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2]) * kInv255;
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

float Image::luminance(int x, int y) const { return luma(pixel(x, y), channels_); }

bool Image::sample_luminance(double x, double y, float* out) const {
  int x0, x1, y0, y1;
  float wx, wy;
  if (!cell(x, width_, &x0, &x1, &wx) || !cell(y, height_, &y0, &y1, &wy)) return false;
  const float a = luma(pixel(x0, y0), channels_), b = luma(pixel(x1, y0), channels_);
  const float c = luma(pixel(x0, y1), channels_), d = luma(pixel(x1, y1), channels_);
  *out = (1 - wy) * ((1 - wx) * a + wx * b) + wy * ((1 - wx) * c + wx * d);
  return true;
}

bool Image::sample_rgb(double x, double y, float out[3]) const {
  int x0, x1, y0, y1;
  float wx, wy;
  if (!cell(x, width_, &x0, &x1, &wx) || !cell(y, height_, &y0, &y1, &wy)) return false;
  const std::uint8_t *a = pixel(x0, y0), *b = pixel(x1, y0), *c = pixel(x0, y1),
                     *d = pixel(x1, y1);
  for (int ch = 0; ch < 3; ++ch) {
    const int k = channels_ == 1 ? 0 : ch;
    out[ch] = ((1 - wy) * ((1 - wx) * a[k] + wx * b[k]) + wy * ((1 - wx) * c[k] + wx * d[k])) *
              kInv255;
  }
  return true;
}

FloatImage FloatImage::luminance_of(const Image& image) {
  FloatImage out;
  out.width_ = image.width();
  out.height_ = image.height();
  out.channels_ = 1;
  out.data_.resize(std::size_t(out.width_) * out.height_);
  for (int y = 0; y < out.height_; ++y)
    for (int x = 0; x < out.width_; ++x)
      out.data_[std::size_t(y) * out.width_ + x] = image.luminance(x, y);
  return out;
}

FloatImage FloatImage::rgb_of(const Image& image) {
  FloatImage out;
  out.width_ = image.width();
  out.height_ = image.height();
  out.channels_ = 3;
  out.data_.resize(std::size_t(out.width_) * out.height_ * 3);
  for (int y = 0; y < out.height_; ++y)
    for (int x = 0; x < out.width_; ++x)
      for (int c = 0; c < 3; ++c)
        out.data_[(std::size_t(y) * out.width_ + x) * 3 + c] =
            image.pixel(x, y)[image.channels() == 1 ? 0 : c] * kInv255;
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

std::shared_ptr<const Image> ImageCache::get(const std::string& path) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = entries_.find(path);
    if (it != entries_.end()) {
      lru_.splice(lru_.begin(), lru_, it->second.lru_position);
      return it->second.image;
    }
  }
  // Decode outside the lock so that threads load different images in parallel.
  auto image = std::make_shared<const Image>(Image::load(path));
  std::lock_guard<std::mutex> lock(mutex_);
  ++loads_;
  auto it = entries_.find(path);
  if (it != entries_.end()) return it->second.image;  // another thread won the race
  lru_.push_front(path);
  entries_[path] = Entry{image, lru_.begin()};
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
