// Image loading and sampling: pixel centres at integers, bilinear inside
// [0, W-1] x [0, H-1], nothing outside.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <thread>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/image.h"
#include "meshnbv/scene.h"
#include "test_util.h"

using namespace meshnbv;

namespace {
Image gradient(int w, int h) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = std::uint8_t(10 * x);
      p[1] = std::uint8_t(20 * y);
      p[2] = std::uint8_t(5 * (x + y));
    }
  return img;
}
}  // namespace

TEST(Image, LuminanceWeights) {
  Image img(1, 1, 3);
  img.pixel(0, 0)[0] = 255;
  EXPECT_NEAR(img.luminance(0, 0), 0.299, 1e-6);
  img.pixel(0, 0)[0] = 0;
  img.pixel(0, 0)[1] = 255;
  EXPECT_NEAR(img.luminance(0, 0), 0.587, 1e-6);
  Image grey(1, 1, 1);
  grey.pixel(0, 0)[0] = 51;
  EXPECT_NEAR(grey.luminance(0, 0), 0.2, 1e-6);
}

TEST(Image, BilinearAtCentresBetweenAndBorders) {
  const Image img = gradient(8, 6);
  float v = -1, rgb[3];
  ASSERT_TRUE(img.sample_luminance(3, 2, &v));
  EXPECT_NEAR(v, img.luminance(3, 2), 1e-6);
  // Channel values are linear in x and y, so bilinear interpolation is exact.
  ASSERT_TRUE(img.sample_rgb(2.25, 4.5, rgb));
  EXPECT_NEAR(rgb[0] * 255, 22.5, 1e-3);
  EXPECT_NEAR(rgb[1] * 255, 90.0, 1e-3);
  EXPECT_NEAR(rgb[2] * 255, 5 * 6.75, 1e-3);
  // Last column and row are inside and exact.
  ASSERT_TRUE(img.sample_rgb(7, 5, rgb));
  EXPECT_NEAR(rgb[0] * 255, 70, 1e-3);
  EXPECT_NEAR(rgb[1] * 255, 100, 1e-3);
  ASSERT_TRUE(img.sample_luminance(0, 0, &v));
  // Outside [0, W-1] x [0, H-1], and NaN: false, output untouched.
  v = -1;
  EXPECT_FALSE(img.sample_luminance(-0.01, 2, &v));
  EXPECT_FALSE(img.sample_luminance(7.01, 2, &v));
  EXPECT_FALSE(img.sample_luminance(2, 5.5, &v));
  EXPECT_FALSE(img.sample_luminance(NAN, 2, &v));
  EXPECT_EQ(v, -1);
}

TEST(Image, SaveLoadRoundTripPngTiffAndGrey) {
  const std::string dir = test::temp_dir("image_io");
  const Image img = gradient(13, 7);
  for (const char* name : {"a.png", "a.tif"}) {
    img.save(dir + "/" + name);
    const Image back = Image::load(dir + "/" + name);
    ASSERT_EQ(back.width(), 13);
    ASSERT_EQ(back.channels(), 3);
    EXPECT_EQ(std::vector<std::uint8_t>(back.data(), back.data() + back.bytes()),
              std::vector<std::uint8_t>(img.data(), img.data() + img.bytes()))
        << name;
  }
  // RGB order survives (OpenCV is BGR inside).
  EXPECT_EQ(Image::load(dir + "/a.png").pixel(3, 0)[0], 30);
  // JPEG is lossy: only close.
  img.save(dir + "/a.jpg");
  EXPECT_NEAR(Image::load(dir + "/a.jpg").pixel(6, 3)[1], 60, 12);
  Image grey(5, 4, 1);
  grey.pixel(2, 1)[0] = 200;
  grey.save(dir + "/g.png");
  const Image g = Image::load(dir + "/g.png");
  EXPECT_EQ(g.channels(), 1);
  EXPECT_EQ(g.pixel(2, 1)[0], 200);
}

TEST(Image, SixteenBitPngAndTiffKeptAt16Bits) {
  const std::string dir = test::temp_dir("image_16");
  // Grey: 1000 and 1001 are one 8-bit level apart by a 257th.
  cv::Mat g(2, 3, CV_16UC1, cv::Scalar(65535));
  g.at<std::uint16_t>(0, 1) = 1000;
  g.at<std::uint16_t>(0, 2) = 1001;
  // RGB (OpenCV stores BGR): pixel (1, 1) has R 40000, G 20000, B 123.
  cv::Mat c(2, 3, CV_16UC3, cv::Scalar(0, 0, 0));
  c.at<cv::Vec<std::uint16_t, 3>>(1, 1) = {123, 20000, 40000};
  for (const char* ext : {".png", ".tif"}) {
    ASSERT_TRUE(cv::imwrite(dir + "/g" + ext, g));
    ASSERT_TRUE(cv::imwrite(dir + "/c" + ext, c));
    const Image grey = Image::load(dir + "/g" + ext);
    ASSERT_EQ(grey.bits(), 16) << ext;
    ASSERT_EQ(grey.channels(), 1);
    EXPECT_EQ(grey.bytes(), 2u * 3u * 2u);
    EXPECT_EQ(grey.pixel16(1, 0)[0], 1000);
    EXPECT_EQ(grey.pixel16(2, 0)[0], 1001);
    EXPECT_FLOAT_EQ(grey.luminance(1, 0), 1000.0f / 65535.0f);
    EXPECT_FLOAT_EQ(grey.luminance(0, 0), 1.0f);
    EXPECT_GT(grey.luminance(2, 0), grey.luminance(1, 0));  // lost at 8 bits
    float v = -1;
    ASSERT_TRUE(grey.sample_luminance(1.5, 0, &v));
    EXPECT_NEAR(v, 1000.5 / 65535.0, 1e-7);
    const FloatImage plane = FloatImage::luminance_of(grey);
    EXPECT_FLOAT_EQ(plane.at(2, 0), 1001.0f / 65535.0f);

    const Image rgb = Image::load(dir + "/c" + ext);
    ASSERT_EQ(rgb.bits(), 16);
    ASSERT_EQ(rgb.channels(), 3);
    EXPECT_EQ(rgb.pixel16(1, 1)[0], 40000);  // RGB order
    EXPECT_EQ(rgb.pixel16(1, 1)[1], 20000);
    EXPECT_EQ(rgb.pixel16(1, 1)[2], 123);
    EXPECT_NEAR(rgb.luminance(1, 1), (0.299 * 40000 + 0.587 * 20000 + 0.114 * 123) / 65535.0, 1e-6);
    EXPECT_FLOAT_EQ(rgb.value(1, 1, 0), 40000.0f / 65535.0f);
    float c3[3];
    ASSERT_TRUE(rgb.sample_rgb(1, 1, c3));
    EXPECT_FLOAT_EQ(c3[1], 20000.0f / 65535.0f);

    // 8 bits on request: round(v / 257).
    const Image eight = rgb.to_8bit();
    EXPECT_EQ(eight.bits(), 8);
    EXPECT_EQ(eight.pixel(1, 1)[0], 156);  // 40000 / 257 = 155.6
    EXPECT_EQ(eight.pixel(1, 1)[2], 0);    // 123 / 257 = 0.48

    // Saved and read back at 16 bits, exactly.
    rgb.save(dir + "/back" + ext);
    const Image back = Image::load(dir + "/back" + ext);
    ASSERT_EQ(back.bits(), 16);
    EXPECT_EQ(std::vector<std::uint8_t>(back.data(), back.data() + back.bytes()),
              std::vector<std::uint8_t>(rgb.data(), rgb.data() + rgb.bytes()));
  }
  // JPEG cannot hold 16 bits: written at 8.
  Image::load(dir + "/c.png").save(dir + "/c.jpg");
  EXPECT_EQ(Image::load(dir + "/c.jpg").bits(), 8);
  // A floating-point TIFF becomes 16-bit, [0, 1] -> [0, 65535].
  cv::Mat f(1, 2, CV_32FC1);
  f.at<float>(0, 0) = 0.25f;
  f.at<float>(0, 1) = 2.0f;  // saturates
  ASSERT_TRUE(cv::imwrite(dir + "/f.tif", f));
  const Image fl = Image::load(dir + "/f.tif");
  ASSERT_EQ(fl.bits(), 16);
  EXPECT_NEAR(fl.pixel16(0, 0)[0], 0.25 * 65535, 1);
  EXPECT_EQ(fl.pixel16(1, 0)[0], 65535);
  // An 8-bit PNG stays 8-bit.
  cv::Mat e(1, 1, CV_8UC1, cv::Scalar(7));
  ASSERT_TRUE(cv::imwrite(dir + "/e.png", e));
  EXPECT_EQ(Image::load(dir + "/e.png").bits(), 8);
}

namespace {
// A 32x16 grey JPEG of four 16x8 quadrants (TL 20, TR 80, BL 160, BR 240),
// block-aligned so JPEG keeps each close to its value, with an Exif APP1
// segment holding only the orientation tag (0x0112) = `orientation`,
// inserted right after SOI as cameras write it.
std::string jpeg_with_orientation(const std::string& dir, int orientation) {
  cv::Mat m(16, 32, CV_8UC1);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x)
      m.at<std::uint8_t>(y, x) = std::uint8_t(y < 8 ? (x < 16 ? 20 : 80) : (x < 16 ? 160 : 240));
  std::vector<std::uint8_t> jpeg;
  EXPECT_TRUE(cv::imencode(".jpg", m, jpeg, {cv::IMWRITE_JPEG_QUALITY, 100}));
  // TIFF little-endian: header (8) + IFD count (2) + one entry (12) + next IFD (4).
  std::vector<std::uint8_t> tiff = {
      'I', 'I', 42, 0, 8, 0, 0, 0, 1, 0, 0x12, 0x01, 3, 0, 1, 0, 0, 0, std::uint8_t(orientation),
      0,   0,   0,  0, 0, 0, 0};
  std::vector<std::uint8_t> app1 = {0xFF, 0xE1, 0, 0, 'E', 'x', 'i', 'f', 0, 0};
  app1.insert(app1.end(), tiff.begin(), tiff.end());
  const std::size_t length = app1.size() - 2;  // the length counts itself, not the marker
  app1[2] = std::uint8_t(length >> 8);
  app1[3] = std::uint8_t(length & 0xFF);
  jpeg.insert(jpeg.begin() + 2, app1.begin(), app1.end());
  const std::string path = dir + "/o" + std::to_string(orientation) + ".jpg";
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(jpeg.data()), std::streamsize(jpeg.size()));
  return path;
}

// The stored pixel that EXIF orientation n shows at (x, y) of the turned
// image, for a stored image W x H (TIFF 6.0 / Exif 2.3 tag 274).
std::pair<int, int> stored_pixel(int n, int x, int y, int W, int H) {
  switch (n) {
    case 1:
      return {x, y};  // as stored
    case 2:
      return {W - 1 - x, y};  // mirrored left-right
    case 3:
      return {W - 1 - x, H - 1 - y};  // turned 180
    case 4:
      return {x, H - 1 - y};  // mirrored top-bottom
    case 5:
      return {y, x};  // transposed
    case 6:
      return {y, H - 1 - x};  // turned 90 clockwise
    case 7:
      return {W - 1 - y, H - 1 - x};  // transversed
    case 8:
      return {W - 1 - y, x};  // turned 90 anticlockwise
  }
  return {-1, -1};
}
}  // namespace

TEST(Image, ExifOrientationAllEightTagsStoredOrTurned) {
  const std::string dir = test::temp_dir("image_exif");
  const int W = 32, H = 16;
  for (int n = 1; n <= 8; ++n) {
    const std::string path = jpeg_with_orientation(dir, n);
    const Image stored = Image::load(path);  // the default: as stored
    ASSERT_EQ(stored.width(), W) << n;
    ASSERT_EQ(stored.height(), H) << n;
    const Image turned = Image::load(path, ImageOrientation::exif);
    const bool swaps = n >= 5;
    ASSERT_EQ(turned.width(), swaps ? H : W) << n;
    ASSERT_EQ(turned.height(), swaps ? W : H) << n;
    // Every pixel of the turned image is the stored pixel the tag names.
    int worst = 0;
    for (int y = 0; y < turned.height(); ++y)
      for (int x = 0; x < turned.width(); ++x) {
        const auto [sx, sy] = stored_pixel(n, x, y, W, H);
        worst = std::max(worst, std::abs(int(turned.pixel(x, y)[0]) - int(stored.pixel(sx, sy)[0])));
      }
    EXPECT_LE(worst, 0) << "orientation " << n;
    // And the quadrants are where the tag says (not a symmetric accident).
    const auto [qx, qy] = stored_pixel(n, 0, 0, W, H);
    EXPECT_NEAR(turned.pixel(0, 0)[0], qy < 8 ? (qx < 16 ? 20 : 80) : (qx < 16 ? 160 : 240), 3) << n;
  }
  // The cache keeps the two readings apart.
  ImageCache cache;
  const std::string p6 = dir + "/o6.jpg";
  EXPECT_EQ(cache.get(p6)->width(), W);
  EXPECT_EQ(cache.get(p6, ImageOrientation::exif)->width(), H);
  EXPECT_EQ(cache.get(p6)->width(), W);
  EXPECT_EQ(cache.loads(), 2u);
}

// The float planes of PRI equal the per-pixel reads bit for bit, for every
// depth and channel count.
TEST(Image, FloatPlanesEqualPerPixelReadsExactly) {
  std::uint32_t state = 12345;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (int bits : {8, 16})
    for (int channels : {1, 3}) {
      Image im(37, 23, channels, bits);
      for (int y = 0; y < im.height(); ++y)
        for (int x = 0; x < im.width(); ++x)
          for (int c = 0; c < channels; ++c) {
            if (bits == 16)
              im.pixel16(x, y)[c] = std::uint16_t(next() >> 16);
            else
              im.pixel(x, y)[c] = std::uint8_t(next() >> 24);
          }
      const FloatImage lum = FloatImage::luminance_of(im), rgb = FloatImage::rgb_of(im);
      int differing = 0;
      for (int y = 0; y < im.height(); ++y)
        for (int x = 0; x < im.width(); ++x) {
          differing += lum.at(x, y) != im.luminance(x, y);
          for (int c = 0; c < 3; ++c) differing += rgb.at(x, y, c) != im.value(x, y, c);
        }
      EXPECT_EQ(differing, 0) << bits << " bits, " << channels << " channels";
    }
}

TEST(Image, MissingAndUndecodableFiles) {
  const std::string dir = test::temp_dir("image_bad");
  MESHNBV_EXPECT_ERROR_CONTAINS(Image::load(dir + "/nope.png"), "not found");
  std::ofstream(dir + "/broken.png") << "\x89PNG\r\n\x1a\n this is not a png";
  MESHNBV_EXPECT_ERROR_CONTAINS(Image::load(dir + "/broken.png"), "does not decode");
}

TEST(ImageCache, BoundedLruAndSharedOwnership) {
  const std::string dir = test::temp_dir("image_cache");
  const Image img = gradient(100, 100);  // 30,000 bytes each
  for (int i = 0; i < 5; ++i) img.save(dir + "/" + std::to_string(i) + ".png");
  ImageCache cache(70000);  // room for two
  auto first = cache.get(dir + "/0.png");
  cache.get(dir + "/1.png");
  cache.get(dir + "/2.png");  // evicts 0
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_LE(cache.bytes_held(), 70000u);
  EXPECT_EQ(first->width(), 100);  // still valid: the caller holds it
  cache.get(dir + "/2.png");
  EXPECT_EQ(cache.loads(), 3u);  // a hit costs no decode
  cache.get(dir + "/0.png");
  EXPECT_EQ(cache.loads(), 4u);  // evicted, so decoded again
  MESHNBV_EXPECT_ERROR_CONTAINS(cache.get(dir + "/missing.png"), "not found");
}

TEST(ImageCache, ManyThreads) {
  const std::string dir = test::temp_dir("image_cache_threads");
  const Image img = gradient(50, 40);
  for (int i = 0; i < 6; ++i) img.save(dir + "/" + std::to_string(i) + ".png");
  ImageCache cache(3 * img.bytes());
  std::vector<std::thread> threads;
  std::atomic<int> failures{0};
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int k = 0; k < 60; ++k) {
        auto im = cache.get(dir + "/" + std::to_string((k + t) % 6) + ".png");
        if (im->width() != 50) ++failures;
      }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_LE(cache.bytes_held(), 3 * img.bytes());
}

// A tool that computed on the photo turned by its EXIF tag (a portrait photo
// stored landscape) gave its camera the turned size: Scene::image and
// load_view_image read the photo turned exactly then, and only then.
TEST(Image, SceneTurnsAStoredPhotoOnItsSideByItsExifTag) {
  const std::string dir = test::temp_dir("image_exif_scene");
  const std::string p6 = jpeg_with_orientation(dir, 6), p1 = jpeg_with_orientation(dir, 1);
  Scene scene;
  View v;
  v.label = "portrait";
  v.camera = test::centred_camera(20, 16, 32);  // the turned size
  v.image_path = p6;
  scene.views.push_back(v);
  v.label = "landscape";
  v.camera = test::centred_camera(20, 32, 16);  // the stored size
  scene.views.push_back(v);
  v.label = "untagged";
  v.camera = test::centred_camera(20, 16, 32);
  v.image_path = p1;
  scene.views.push_back(v);

  const Image turned = Image::load(p6, ImageOrientation::exif);
  const auto same = [](const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::equal(a.data(), a.data() + a.bytes(), b.data());
  };
  EXPECT_TRUE(same(*scene.image(0), turned));
  EXPECT_TRUE(same(*load_view_image(scene.views[0]), turned));
  EXPECT_TRUE(same(*scene.image(1), Image::load(p6)));
  // No tag to turn it by: refused, saying so.
  MESHNBV_EXPECT_ERROR_CONTAINS(
      scene.image(2),
      "image is 32x16 but its camera says 16x32 (turned by its EXIF orientation it is still 32x16)");
  MESHNBV_EXPECT_ERROR_CONTAINS(load_view_image(scene.views[2]), "still 32x16");
  // Asked for explicitly, the EXIF reading is used as it is.
  scene.views[1].orientation = ImageOrientation::exif;
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.image(1), "image is 16x32 but its camera says 32x16");
}

namespace image_reduction_test {
// A grey 250x190 JPEG (sides no multiple of 8) of a smooth pattern,
// 0.5 + 0.35 sin(2 pi x / 96) cos(2 pi y / 96), at quality 100.
std::string smooth_jpeg(const std::string& dir) {
  cv::Mat m(190, 250, CV_8UC1);
  for (int y = 0; y < 190; ++y)
    for (int x = 0; x < 250; ++x)
      m.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(
          255.0 * (0.5 + 0.35 * std::sin(2 * M_PI * x / 96.0) * std::cos(2 * M_PI * y / 96.0)));
  const std::string path = dir + "/smooth.jpg";
  EXPECT_TRUE(cv::imwrite(path, m, {cv::IMWRITE_JPEG_QUALITY, 100}));
  EXPECT_TRUE(cv::imwrite(dir + "/smooth.png", m));
  return path;
}

// RMS difference between the full image at (x, y) and the reduced one at
// map(x), over a grid of points 20 px inside the border.
template <class Map>
double rms_against_full(const Image& full, const Image& reduced, Map map) {
  double sum = 0;
  int n = 0;
  for (double y = 20; y < full.height() - 20; y += 3.7)
    for (double x = 20; x < full.width() - 20; x += 3.3) {
      float a, b;
      EXPECT_TRUE(full.sample_luminance(x, y, &a));
      EXPECT_TRUE(reduced.sample_luminance(map(x), map(y), &b));
      sum += double(a - b) * double(a - b);
      ++n;
    }
  return std::sqrt(sum / n);
}
}  // namespace image_reduction_test

// A JPEG decoded k times smaller (libjpeg's DCT scaling) is ceil(W/k) x
// ceil(H/k), and its pixel j is centred on full-resolution pixel
// k j + (k - 1) / 2: read through x' = (x + 0.5) / k - 0.5 it matches the
// full image far better than through x / k (an offset of (k - 1) / 2 px).
TEST(Image, ReducedJpegIsSmallerAndCentredOnItsBlocks) {
  using namespace image_reduction_test;
  const std::string dir = test::temp_dir("image_reduced");
  const std::string path = smooth_jpeg(dir);
  const Image full = Image::load(path);
  ASSERT_EQ(full.reduction(), 1);
  for (int k : {2, 4, 8}) {
    const Image r = Image::load(path, ImageOrientation::stored, k);
    EXPECT_EQ(r.reduction(), k);
    EXPECT_EQ(r.width(), (250 + k - 1) / k) << k;
    EXPECT_EQ(r.height(), (190 + k - 1) / k) << k;
    const double centred = rms_against_full(full, r, [k](double x) { return (x + 0.5) / k - 0.5; });
    const double naive = rms_against_full(full, r, [k](double x) { return x / k; });
    // What is left is the low pass: the k-pixel block average and the
    // bilinear reads between reduced pixels flatten the pattern's peaks
    // (about 0.002 of RMS per pixel of k on this 96-px pattern).
    EXPECT_LT(centred, 0.002 * k) << k;
    EXPECT_LT(3 * centred, naive) << k;
  }
  // Another format is decoded whole, and says so.
  const Image png = Image::load(dir + "/smooth.png", ImageOrientation::stored, 4);
  EXPECT_EQ(png.reduction(), 1);
  EXPECT_EQ(png.width(), 250);
  EXPECT_TRUE(is_jpeg_file(path));
  EXPECT_FALSE(is_jpeg_file(dir + "/smooth.png"));
  EXPECT_FALSE(is_jpeg_file(dir + "/none.jpg"));
  MESHNBV_EXPECT_ERROR_CONTAINS(Image::load(path, ImageOrientation::stored, 3), "must be 1, 2, 4 or 8");
  // The cache keeps each reduction apart.
  ImageCache cache;
  EXPECT_EQ(cache.get(path)->width(), 250);
  EXPECT_EQ(cache.get(path, ImageOrientation::stored, 2)->width(), 125);
  EXPECT_EQ(cache.get(path, ImageOrientation::stored, 2)->width(), 125);
  EXPECT_EQ(cache.loads(), 2u);
}

// Scene::image checks a reduced photo against its camera's size divided
// (rounded up), also when it is turned by its EXIF tag.
TEST(Image, SceneReadsAReducedPhotoAgainstItsCamera) {
  using namespace image_reduction_test;
  const std::string dir = test::temp_dir("image_reduced_scene");
  const std::string path = smooth_jpeg(dir);
  Scene scene;
  View v;
  v.label = "jpeg";
  v.camera = test::centred_camera(200, 250, 190);
  v.image_path = path;
  scene.views.push_back(v);
  v.label = "png";
  v.image_path = dir + "/smooth.png";
  scene.views.push_back(v);
  v.label = "portrait";
  v.camera = test::centred_camera(20, 16, 32);
  v.image_path = jpeg_with_orientation(dir, 6);
  scene.views.push_back(v);
  const auto a = scene.image(0, 4);
  EXPECT_EQ(a->reduction(), 4);
  EXPECT_EQ(a->width(), 63);
  EXPECT_EQ(a->height(), 48);
  EXPECT_EQ(scene.image(1, 4)->reduction(), 1);
  EXPECT_EQ(scene.image(1, 4)->width(), 250);
  const auto turned = scene.image(2, 2);
  EXPECT_EQ(turned->reduction(), 2);
  EXPECT_EQ(turned->width(), 8);
  EXPECT_EQ(turned->height(), 16);
  scene.views[0].camera = test::centred_camera(200, 256, 190);
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.image(0, 4), "image is 63x48 decoded 4 times smaller but its camera says 256x190");
}
