// Raster images for the core: QImage -> meshnbv::Image equals the core's own
// decoding of the same file (8- and 16-bit PNG, RGB, ARGB, grey; JPEG), and
// a document's rasters reach the core in memory: with the image files
// deleted after MeshLab loaded them, PRI is bitwise the PRI of the same
// scene read from the files.
#include <cstring>
#include <filesystem>
#include <random>

#include <QDir>
#include <QImage>
#include <QRgba64>

#include <gtest/gtest.h>

#include <common/meshmodel.h>

#include "document_scene.h"
#include "meshlab_test_support.h"
#include "meshnbv/error.h"
#include "meshnbv/image.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/pri.h"
#include "raster_images.h"
#include "shot_conversion.h"

using namespace meshnbv;
using meshnbv::meshlab::image_from_qimage;
namespace fs = std::filesystem;

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
  ASSERT_EQ(a.bits(), b.bits());
  int differing = 0;
  for (std::size_t i = 0; i < a.bytes(); ++i) differing += a.data()[i] != b.data()[i];
  EXPECT_EQ(differing, 0);
}

// The running test's name, for its scratch folder.
std::string scratch_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

}  // namespace

#define MESHNBV_EXPECT_ERROR(statement, fragment)                                        \
  do {                                                                                  \
    try {                                                                               \
      statement;                                                                        \
      ADD_FAILURE() << "expected meshnbv::Error containing '" << (fragment) << "'";     \
    } catch (const meshnbv::Error& e_) {                                                \
      EXPECT_NE(std::string(e_.what()).find(fragment), std::string::npos) << e_.what(); \
    }                                                                                   \
  } while (0)

TEST(RasterImages, QImageEqualsCoreDecodingOfTheSamePng) {
  const QDir dir(QString::fromStdString(meshlab_test::scratch_dir(scratch_name())));
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

TEST(RasterImages, SixteenBitQImageEqualsCoreDecodingOfTheSamePng) {
  const QDir dir(QString::fromStdString(meshlab_test::scratch_dir(scratch_name())));
  std::mt19937 rng(7);
  QImage colour(29, 17, QImage::Format_RGBA64);
  QImage grey(29, 17, QImage::Format_Grayscale16);
  for (int y = 0; y < 17; ++y) {
    QRgba64* c = reinterpret_cast<QRgba64*>(colour.scanLine(y));
    quint16* g = reinterpret_cast<quint16*>(grey.scanLine(y));
    for (int x = 0; x < 29; ++x) {
      c[x] = QRgba64::fromRgba64(quint16(rng()), quint16(rng()), quint16(rng()), quint16(rng()));
      g[x] = quint16(rng());
    }
  }
  for (const QImage* image : {&colour, &grey}) {
    const QString path = dir.filePath(image == &grey ? "grey16.png" : "colour16.png");
    ASSERT_TRUE(image->save(path));
    const QImage loaded(path);
    ASSERT_FALSE(loaded.isNull());
    SCOPED_TRACE(int(loaded.format()));
    const Image ours = image_from_qimage(loaded);
    EXPECT_EQ(ours.channels(), image == &grey ? 1 : 3);
    EXPECT_EQ(ours.bits(), 16);  // kept at 16 bits, as the core keeps the file
    expect_equal(ours, Image::load(path.toStdString()));
  }
}

TEST(RasterImages, JpegQImageEqualsCoreDecodingOfTheSameFile) {
  const QDir dir(QString::fromStdString(meshlab_test::scratch_dir(scratch_name())));
  const QString path = dir.filePath("photo.jpg");
  ASSERT_TRUE(noise(64, 48, QImage::Format_RGB32, 9).save(path, "JPEG", 90));
  const QImage loaded(path);
  ASSERT_FALSE(loaded.isNull());
  expect_equal(image_from_qimage(loaded), Image::load(path.toStdString()));
}

TEST(RasterImages, NullImageIsAnError) {
  EXPECT_THROW(image_from_qimage(QImage()), Error);
}

// A document built in process from the fixture project: the mesh layer and
// one raster per view, each plane loaded by MeshLab's own Plane (QImage).
TEST(DocumentScene, RasterImagesReachTheCoreInMemory) {
  const std::string dir = meshlab_test::project_copy("document_in_memory");
  const Scene files = io::read_scene(dir + "/ml.mlp");
  ASSERT_EQ(files.views.size(), 8u);
  MeshDocument document;
  MeshModel* model = document.addNewMesh("", "mesh", true);
  meshlab::fill_model(files.mesh, *model);
  for (const View& v : files.views) {
    RasterModel* raster = document.addNewRaster();
    raster->setLabel(QString::fromStdString(v.label));
    raster->shot = meshlab::shot_from_camera(v.camera);
    raster->addPlane(new Plane(QString::fromStdString(v.image_path), Plane::RGBA));
  }
  const meshlab::DocumentScene ds = meshlab::scene_from_document(document, *model);
  ASSERT_EQ(ds.views_with_image, 8);
  // The same scene (same float cameras and mesh) with the images from files.
  Scene from_files = ds.scene;
  for (std::size_t i = 0; i < from_files.views.size(); ++i) {
    EXPECT_TRUE(ds.scene.views[i].image_in_memory());
    EXPECT_TRUE(ds.scene.views[i].image_path.empty());
    from_files.views[i].pixels.reset();
    from_files.views[i].image_path = files.views[i].image_path;
  }
  PriOptions colour;
  colour.measure = Measure::NCC;
  colour.color = true;
  const PriResult ssd = compute_pri(from_files), ncc = compute_pri(from_files, colour);

  fs::remove_all(fs::path(dir) / "images");  // MeshLab holds the pixels; no file is left
  const PriResult ssd_memory = compute_pri(ds.scene), ncc_memory = compute_pri(ds.scene, colour);
  ASSERT_GT(ssd.observed, 1000u);
  for (const auto& [a, b] : {std::make_pair(&ssd, &ssd_memory), std::make_pair(&ncc, &ncc_memory)}) {
    ASSERT_EQ(a->pri.size(), b->pri.size());
    EXPECT_EQ(std::memcmp(a->pri.data(), b->pri.data(), a->pri.size() * sizeof(float)), 0)
        << "PRI from memory differs from PRI from files";
    EXPECT_EQ(a->pri_views, b->pri_views);
  }
  std::cout << ssd.observed << " observed faces: PRI from the rasters' pixels bitwise equals PRI "
            << "from the files (ssd and ncc colour)\n";

  // A plane MeshLab could not load keeps its file, which the core names.
  RasterModel* broken = document.addNewRaster();
  broken->setLabel("broken");
  broken->shot = meshlab::shot_from_camera(files.views[0].camera);
  const std::string gone = dir + "/images/view_000.png";
  broken->addPlane(new Plane(QString::fromStdString(gone), Plane::RGBA));
  meshlab::DocumentScene with_broken = meshlab::scene_from_document(document, *model);
  EXPECT_EQ(with_broken.scene.views.back().image_path, gone);
  MESHNBV_EXPECT_ERROR(compute_pri(with_broken.scene), "image file not found");
}
