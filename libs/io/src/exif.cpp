// EXIF GPS and focal length through exiv2 (exif.h).
#include "meshnbv/io/exif.h"

#include <cmath>
#include <exiv2/exiv2.hpp>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"

namespace meshnbv::io {
namespace {

void mute_exiv2_log() {
  static std::once_flag once;
  std::call_once(once, [] { Exiv2::LogMsg::setLevel(Exiv2::LogMsg::mute); });
}

const Exiv2::Exifdatum* find(const Exiv2::ExifData& exif, const char* key) {
  const auto it = exif.findKey(Exiv2::ExifKey(key));
  return it == exif.end() ? nullptr : &*it;
}

double rational(const Exiv2::Exifdatum& d, long i, const std::string& file) {
  const Exiv2::Rational r = d.toRational(i);
  if (r.second == 0) throw Error("malformed EXIF: " + d.key() + " has a zero denominator", file);
  return double(r.first) / double(r.second);
}

// Degrees, minutes, seconds (three rationals) with a hemisphere reference.
std::optional<double> coordinate(const Exiv2::ExifData& exif, const char* key, const char* ref_key,
                                 char positive, char negative, double limit, const std::string& file) {
  const Exiv2::Exifdatum* d = find(exif, key);
  if (!d) return std::nullopt;
  if (d->count() != 3 || d->typeId() != Exiv2::unsignedRational)
    throw Error("malformed EXIF: " + d->key() + " must be three unsigned rationals", file);
  const double value = rational(*d, 0, file) + rational(*d, 1, file) / 60.0 + rational(*d, 2, file) / 3600.0;
  if (!std::isfinite(value) || value > limit)
    throw Error("malformed EXIF: " + d->key() + " is " + format_option_value(value) + " degrees, beyond " +
                    format_option_value(limit),
                file);
  const Exiv2::Exifdatum* r = find(exif, ref_key);
  const std::string ref = r ? r->toString() : std::string();
  if (ref.empty() || (ref[0] != positive && ref[0] != negative))
    throw Error(std::string("malformed EXIF: ") + ref_key + " must be " + positive + " or " + negative +
                    ", got '" + ref + "'",
                file);
  return ref[0] == negative ? -value : value;
}

ExifInfo from_image(Exiv2::Image& image, const std::string& file) {
  image.readMetadata();
  const Exiv2::ExifData& exif = image.exifData();
  ExifInfo info;
  info.latitude =
      coordinate(exif, "Exif.GPSInfo.GPSLatitude", "Exif.GPSInfo.GPSLatitudeRef", 'N', 'S', 90.0, file);
  info.longitude =
      coordinate(exif, "Exif.GPSInfo.GPSLongitude", "Exif.GPSInfo.GPSLongitudeRef", 'E', 'W', 180.0, file);
  if (const Exiv2::Exifdatum* a = find(exif, "Exif.GPSInfo.GPSAltitude")) {
    double alt = rational(*a, 0, file);
    if (const Exiv2::Exifdatum* r = find(exif, "Exif.GPSInfo.GPSAltitudeRef"))
      if (r->count() > 0 && r->toLong(0) == 1) alt = -alt;
    info.altitude = alt;
  }
  if (const Exiv2::Exifdatum* f = find(exif, "Exif.Photo.FocalLength")) {
    const double mm = rational(*f, 0, file);
    if (!(mm > 0) || !std::isfinite(mm))
      throw Error("malformed EXIF: Exif.Photo.FocalLength must be positive", file);
    info.focal_length_mm = mm;
  }
  if (const Exiv2::Exifdatum* f = find(exif, "Exif.Photo.FocalLengthIn35mmFilm"))
    if (f->count() > 0 && f->toLong(0) > 0) info.focal_length_35mm = double(f->toLong(0));
  return info;
}

}  // namespace

namespace {

ExifInfo read_exif_file(const std::string& path, bool unknown_ok, bool* unknown) {
  mute_exiv2_log();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error("cannot open the file", path);
  try {
    if (unknown_ok && Exiv2::ImageFactory::getType(path) == Exiv2::ImageType::none) {
      *unknown = true;
      return {};
    }
    auto image = Exiv2::ImageFactory::open(path);
    if (!image.get()) throw Error("not an image with EXIF that exiv2 reads", path);
    return from_image(*image, path);
  } catch (const Exiv2::AnyError& e) {
    throw Error(std::string("cannot read EXIF: ") + e.what(), path);
  }
}

}  // namespace

ExifInfo read_exif(const std::string& path) {
  bool unknown = false;
  return read_exif_file(path, false, &unknown);
}

std::optional<ExifInfo> read_exif_if_known_type(const std::string& path) {
  bool unknown = false;
  ExifInfo e = read_exif_file(path, true, &unknown);
  if (unknown) return std::nullopt;
  return e;
}

ExifInfo read_exif_from_memory(const std::string& bytes, const std::string& name) {
  mute_exiv2_log();
  try {
    auto image =
        Exiv2::ImageFactory::open(reinterpret_cast<const Exiv2::byte*>(bytes.data()), long(bytes.size()));
    if (!image.get()) throw Error("not an image with EXIF that exiv2 reads", name);
    return from_image(*image, name);
  } catch (const Exiv2::AnyError& e) {
    throw Error(std::string("cannot read EXIF: ") + e.what(), name);
  }
}

namespace {

// `head`: the file's first bytes (PNG's IHDR for its bit depth).
PhotoHeader header_of(Exiv2::Image& image, const std::string& head) {
  image.readMetadata();
  PhotoHeader h;
  h.width = image.pixelWidth();
  h.height = image.pixelHeight();
  const Exiv2::ExifData& exif = image.exifData();
  if (const Exiv2::Exifdatum* o = find(exif, "Exif.Image.Orientation"))
    if (o->count() > 0 && o->toLong(0) >= 1 && o->toLong(0) <= 8) h.orientation = int(o->toLong(0));
  const int type = image.imageType();
  if (type == Exiv2::ImageType::jpeg) {
    h.bits = 8;
  } else if (type == Exiv2::ImageType::png) {
    // IHDR is the first chunk: signature (8), length (4), "IHDR" (4),
    // width (4), height (4), bit depth (1).
    if (head.size() >= 25 && head.compare(12, 4, "IHDR") == 0) h.bits = static_cast<unsigned char>(head[24]);
  } else if (const Exiv2::Exifdatum* b = find(exif, "Exif.Image.BitsPerSample")) {
    if (b->count() > 0 && b->toLong(0) > 0 && b->toLong(0) <= 64) h.bits = int(b->toLong(0));
  }
  return h;
}

}  // namespace

std::optional<PhotoHeader> read_photo_header(const std::string& path) {
  mute_exiv2_log();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error("cannot open the file", path);
  try {
    if (Exiv2::ImageFactory::getType(path) == Exiv2::ImageType::none) return std::nullopt;
    auto image = Exiv2::ImageFactory::open(path);
    if (!image.get()) throw Error("not an image that exiv2 reads", path);
    std::string head(25, '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(&head[0], std::streamsize(head.size()));
    head.resize(std::size_t(in.gcount()));
    return header_of(*image, head);
  } catch (const Exiv2::AnyError& e) {
    throw Error(std::string("cannot read the photo's header: ") + e.what(), path);
  }
}

std::optional<PhotoHeader> read_photo_header_from_memory(const std::string& bytes, const std::string& name) {
  mute_exiv2_log();
  try {
    const auto* b = reinterpret_cast<const Exiv2::byte*>(bytes.data());
    if (Exiv2::ImageFactory::getType(b, long(bytes.size())) == Exiv2::ImageType::none) return std::nullopt;
    auto image = Exiv2::ImageFactory::open(b, long(bytes.size()));
    if (!image.get()) throw Error("not an image that exiv2 reads", name);
    return header_of(*image, bytes.substr(0, 25));
  } catch (const Exiv2::AnyError& e) {
    throw Error(std::string("cannot read the photo's header: ") + e.what(), name);
  }
}

}  // namespace meshnbv::io
