// 8- and 16-bit images loaded through OpenCV (PNG, JPEG, TIFF, ...) and a
// bounded, thread-safe cache so that scenes with hundreds of large photos
// never hold them all in memory.
#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace meshnbv {

// Which way a photo's pixels are read. `stored`: as the file stores them,
// the EXIF orientation tag ignored (what COLMAP, OpenMVG and AliceVision
// compute on). `exif`: turned as the EXIF orientation tag says (JPEG), as a
// viewer shows the photo.
enum class ImageOrientation { stored, exif };

// True when the file starts as a JPEG does (FF D8 FF): the files that
// Image::load can decode reduced.
bool is_jpeg_file(const std::string& path);

class Image {
 public:
  Image() = default;
  // Black image; channels 1 (grey) or 3 (RGB); bits 8 or 16 per channel.
  Image(int width, int height, int channels, int bits = 8);

  // Throws Error when the file is missing or does not decode. Grey images
  // stay grey, colour images become RGB (alpha dropped); 16-bit files stay
  // 16-bit, floating-point ones become 16-bit ([0, 1] -> [0, 65535]).
  // `reduction` (1, 2, 4 or 8): a JPEG file is decoded that many times
  // smaller on each side by the decoder's DCT scaling (libjpeg's
  // scale_denom: ceil(W / reduction) x ceil(H / reduction), reduced pixel j
  // centred on full-resolution pixel reduction j + (reduction - 1) / 2, an
  // average of its block); any other format at full resolution.
  // reduction() tells which was done.
  static Image load(const std::string& path, ImageOrientation orientation = ImageOrientation::stored,
                    int reduction = 1);
  // Writes PNG/JPEG/TIFF by extension; throws Error on failure. A 16-bit
  // image goes to PNG and TIFF at 16 bits, to other formats at 8.
  void save(const std::string& path) const;

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  int bits() const { return bits_; }
  bool empty() const { return width_ == 0; }
  // How many times smaller on each side than its file this image was
  // decoded (load's `reduction` where it applied; 1 otherwise).
  int reduction() const { return reduction_; }
  std::size_t bytes() const { return bits_ == 16 ? data16_.size() * 2 : data_.size(); }
  // The raw samples, row-major, channels interleaved: bytes() bytes
  // (native-endian 16-bit values for bits() == 16).
  const std::uint8_t* data() const {
    return bits_ == 16 ? reinterpret_cast<const std::uint8_t*>(data16_.data()) : data_.data();
  }
  std::uint8_t* data() {
    return bits_ == 16 ? reinterpret_cast<std::uint8_t*>(data16_.data()) : data_.data();
  }
  // 8-bit images only (bits() == 8).
  std::uint8_t* pixel(int x, int y) { return &data_[(std::size_t(y) * width_ + x) * channels_]; }
  const std::uint8_t* pixel(int x, int y) const {
    return &data_[(std::size_t(y) * width_ + x) * channels_];
  }
  // 16-bit images only (bits() == 16).
  std::uint16_t* pixel16(int x, int y) { return &data16_[(std::size_t(y) * width_ + x) * channels_]; }
  const std::uint16_t* pixel16(int x, int y) const {
    return &data16_[(std::size_t(y) * width_ + x) * channels_];
  }
  // The same image at 8 bits (round(v / 257)); a copy of an 8-bit one.
  Image to_8bit() const;
  // Channel c of pixel (x, y) in [0, 1] (value / 255 or / 65535).
  float value(int x, int y, int c) const;

  // 0.299 R + 0.587 G + 0.114 B, in [0, 1] (grey: value / 255 or / 65535).
  float luminance(int x, int y) const;

  // Bilinear sampling at continuous coordinates with pixel centres at
  // integers. Defined on [0, W-1] x [0, H-1] (the SPEC's "inside the
  // image"); returns false outside, and for NaN coordinates, leaving the
  // output untouched. On the last row/column it interpolates with weight 0
  // on the missing neighbour, so the border value is exact.
  bool sample_luminance(double x, double y, float* out) const;
  // Per channel in [0, 1]; a grey image gives three equal values.
  bool sample_rgb(double x, double y, float out[3]) const;

 private:
  int width_ = 0, height_ = 0, channels_ = 0, bits_ = 8, reduction_ = 1;
  std::vector<std::uint8_t> data_;     // bits_ == 8
  std::vector<std::uint16_t> data16_;  // bits_ == 16
};

// Float planes for fast repeated sampling (photo-consistency): luminance
// (1 channel) or RGB (3 channels) in [0, 1], with the same bilinear rule
// as Image.
class FloatImage {
 public:
  // Rows converted in parallel.
  static FloatImage luminance_of(const Image& image);
  static FloatImage rgb_of(const Image& image);

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  float at(int x, int y, int c = 0) const {
    return data_[(std::size_t(y) * width_ + x) * channels_ + c];
  }
  // The samples, row-major, channels interleaved.
  const float* data() const { return data_.data(); }
  // Writes channels() values; false outside [0, W-1] x [0, H-1] or for NaN.
  bool sample(double x, double y, float* out) const;
  // The same for a one-channel plane, inline for the photo-consistency
  // inner loop. On the last row/column the cell is clamped and the weight
  // is 1, which gives the same value as sample().
  bool sample_gray(double x, double y, float* out) const {
    if (!(x >= 0.0 && y >= 0.0 && x <= width_ - 1.0 && y <= height_ - 1.0)) return false;
    if (width_ < 2 || height_ < 2) return sample(x, y, out);
    int ix = static_cast<int>(x), iy = static_cast<int>(y);
    if (ix > width_ - 2) ix = width_ - 2;
    if (iy > height_ - 2) iy = height_ - 2;
    const float wx = static_cast<float>(x - ix), wy = static_cast<float>(y - iy);
    const float* r0 = &data_[std::size_t(iy) * width_ + ix];
    const float* r1 = r0 + width_;
    *out = (1 - wy) * ((1 - wx) * r0[0] + wx * r0[1]) + wy * ((1 - wx) * r1[0] + wx * r1[1]);
    return true;
  }

 private:
  int width_ = 0, height_ = 0, channels_ = 0;
  std::vector<float> data_;
};

// Least-recently-used cache of decoded images, bounded in bytes. get() is
// thread-safe; a returned image stays valid while the caller holds it even
// if the cache evicts it.
class ImageCache {
 public:
  explicit ImageCache(std::size_t max_bytes = std::size_t(1) << 30);

  // The file decoded with that orientation and reduction (Image::load;
  // each its own entry).
  std::shared_ptr<const Image> get(const std::string& path,
                                   ImageOrientation orientation = ImageOrientation::stored, int reduction = 1);
  void clear();
  std::size_t bytes_held() const;
  std::size_t max_bytes() const { return max_bytes_; }
  std::size_t size() const;
  std::size_t loads() const;  // decodes done so far (misses)

 private:
  struct Entry {
    std::shared_ptr<const Image> image;
    std::list<std::string>::iterator lru_position;
  };
  void evict_locked();

  std::size_t max_bytes_;
  mutable std::mutex mutex_;
  std::list<std::string> lru_;  // front = most recent
  std::unordered_map<std::string, Entry> entries_;
  std::size_t bytes_ = 0;
  std::size_t loads_ = 0;
};

}  // namespace meshnbv
