// Raster images for the core: QImage -> meshnbv::Image equals the core's own
// decoding of the same file, and images without a readable file reach the
// core through lossless temporary copies.
#include <filesystem>
#include <random>

#include <QImage>
#include <QTemporaryDir>

#include <gtest/gtest.h>

#include "meshnbv/error.h"
#include "meshnbv/image.h"
#include "raster_images.h"

using namespace meshnbv;
using meshnbv::meshlab::image_from_qimage;
using meshnbv::meshlab::RasterImageFiles;

namespace {

QImage noise(int w, int h, QImage::Format format, unsigned seed) {
  QImage image(w, h, format);
  std::mt19937 rng(seed);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image.setPixel(x, y, format == QImage::Format_Grayscale8 ? 0 : qRgba(rng() & 255, rng() & 255, rng() & 255, rng() & 255));
  if (format == QImage::Format_Grayscale8)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) image.scanLine(y)[x] = uchar(rng() & 255);
  return image;
}

void expect_equal(const Image& a, const Image& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  ASSERT_EQ(a.channels(), b.channels());
  int differing = 0;
  for (std::size_t i = 0; i < a.bytes(); ++i) differing += a.data()[i] != b.data()[i];
  EXPECT_EQ(differing, 0);
}

}  // namespace

TEST(RasterImages, QImageEqualsCoreDecodingOfTheSamePng) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const struct {
    QImage::Format format;
    int channels;
  } cases[] = {{QImage::Format_RGB32, 3}, {QImage::Format_ARGB32, 3}, {QImage::Format_Grayscale8, 1}};
  unsigned seed = 1;
  for (const auto& c : cases) {
    SCOPED_TRACE(int(c.format));
    const QImage original = noise(37, 23, c.format, seed++);
    const QString path = dir.filePath(QString("img_%1.png").arg(seed));
    ASSERT_TRUE(original.save(path));
    const QImage loaded(path);  // as MeshLab's Plane loads it
    ASSERT_FALSE(loaded.isNull());
    const Image ours = image_from_qimage(loaded);
    EXPECT_EQ(ours.channels(), c.channels);
    expect_equal(ours, Image::load(path.toStdString()));
  }
}

TEST(RasterImages, ExistingFileIsPassedByPath) {
  QTemporaryDir dir;
  const QString path = dir.filePath("a.png");
  ASSERT_TRUE(noise(8, 6, QImage::Format_RGB32, 3).save(path));
  RasterImageFiles files;
  EXPECT_EQ(files.path_for(path.toStdString(), QImage(path), "a"), path.toStdString());
  EXPECT_EQ(files.copies(), 0);
}

TEST(RasterImages, ImageWithoutFileGoesThroughALosslessCopy) {
  const QImage rgb = noise(16, 9, QImage::Format_RGB32, 4);
  const QImage grey = noise(16, 9, QImage::Format_Grayscale8, 5);
  std::string rgb_path, grey_path;
  {
    RasterImageFiles files;
    rgb_path = files.path_for("/nonexistent/meshnbv/a.jpg", rgb, "a");
    grey_path = files.path_for("", grey, "b");
    EXPECT_EQ(files.copies(), 2);
    expect_equal(Image::load(rgb_path), image_from_qimage(rgb));
    expect_equal(Image::load(grey_path), image_from_qimage(grey));
    EXPECT_EQ(Image::load(grey_path).channels(), 1);
  }
  EXPECT_FALSE(std::filesystem::exists(rgb_path)) << "temporary copies outlive their owner";
}

TEST(RasterImages, NeitherFileNorImageIsAnError) {
  RasterImageFiles files;
  try {
    files.path_for("/nonexistent/meshnbv/a.png", QImage(), "view_3");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("view_3"), std::string::npos) << e.what();
  }
}
