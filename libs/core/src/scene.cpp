#include "meshnbv/scene.h"

#include <algorithm>

#include "meshnbv/error.h"

namespace meshnbv {
namespace {

void check_one_source(const View& view) {
  if (!view.image_path.empty() && view.pixels)
    throw Error("has both an image file and an in-memory image; set one (image_path or pixels)",
                view.image_path, -1, "view '" + view.label + "'");
}

// A file-backed view's photo through `get(orientation)`, checked against its
// camera's size; a stored photo lying on its side is tried turned by its
// EXIF tag.
template <class Get>
std::shared_ptr<const Image> file_image(const View& view, Get get) {
  auto img = get(view.orientation);
  // A reduced decode (Image::reduction) is ceil(size / reduction) a side.
  const auto reduced = [](int size, int r) { return (size + r - 1) / r; };
  const auto fits = [&](const Image& im) {
    return im.width() == reduced(view.camera.width, im.reduction()) &&
           im.height() == reduced(view.camera.height, im.reduction());
  };
  if (fits(*img)) return img;
  std::string note;
  if (view.orientation == ImageOrientation::stored &&
      img->width() == reduced(view.camera.height, img->reduction()) &&
      img->height() == reduced(view.camera.width, img->reduction())) {
    // Stored on its side: the tool saw the photo turned by its EXIF tag.
    auto turned = get(ImageOrientation::exif);
    if (fits(*turned)) return turned;
    note = " (turned by its EXIF orientation it is still " + std::to_string(turned->width()) + "x" +
           std::to_string(turned->height()) + ")";
  }
  const std::string reduced_note =
      img->reduction() > 1 ? " decoded " + std::to_string(img->reduction()) + " times smaller" : "";
  throw Error("image is " + std::to_string(img->width()) + "x" + std::to_string(img->height()) + reduced_note +
                  " but its camera says " + std::to_string(view.camera.width) + "x" +
                  std::to_string(view.camera.height) + note,
              view.image_path, -1, "view '" + view.label + "'");
}

}  // namespace

const std::string& View::image_file(const std::string& purpose) const {
  if (pixels)
    throw Error("its image is held in memory, not in a file, and " + purpose +
                    " can only reference image files (save it with Image::save and set image_path)",
                {}, -1, "view '" + label + "'");
  return image_path;
}

std::shared_ptr<const Image> Scene::image(std::size_t i, int reduction) const {
  if (i >= views.size()) throw Error("view index " + std::to_string(i) + " out of range");
  const View& view = views[i];
  if (!view.has_image()) throw Error("view '" + view.label + "' has no image");
  check_one_source(view);
  if (!view.pixels)
    return file_image(view, [&](ImageOrientation o) { return images->get(view.image_path, o, reduction); });
  const Image& im = *view.pixels;
  if (im.width() != view.camera.width || im.height() != view.camera.height)
    throw Error("in-memory image is " + std::to_string(im.width()) + "x" + std::to_string(im.height()) +
                    " but its camera says " + std::to_string(view.camera.width) + "x" +
                    std::to_string(view.camera.height),
                {}, -1, "view '" + view.label + "'");
  return view.pixels;
}

std::shared_ptr<const Image> load_view_image(const View& view) {
  if (view.image_path.empty()) throw Error("view '" + view.label + "' has no image file");
  return file_image(view, [&](ImageOrientation o) {
    return std::make_shared<const Image>(Image::load(view.image_path, o));
  });
}

std::size_t Scene::num_views_with_image() const {
  std::size_t n = 0;
  for (const auto& v : views) n += v.has_image() ? 1 : 0;
  return n;
}

void Scene::validate() const {
  mesh.validate(mesh_path);
  for (const auto& v : views) {
    v.camera.check("view '" + v.label + "'");
    check_one_source(v);
  }
}

ReprojectionStats reprojection_error(const Scene& scene) {
  ReprojectionStats stats;
  std::vector<double> errors;
  for (const SparsePoint& p : scene.sparse_points)
    for (const auto& [view, pixel] : p.observations) {
      if (view < 0 || std::size_t(view) >= scene.views.size()) continue;
      Vec2 projected;
      if (!scene.views[std::size_t(view)].camera.project(p.position, &projected)) {
        ++stats.behind;
        continue;
      }
      errors.push_back((projected - pixel).norm());
    }
  stats.observations = errors.size();
  if (errors.empty()) return stats;
  double sum = 0;
  for (double e : errors) sum += e;
  stats.mean = sum / double(errors.size());
  stats.max = *std::max_element(errors.begin(), errors.end());
  const std::size_t mid = errors.size() / 2;
  std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(mid), errors.end());
  stats.median = errors[mid];
  if (errors.size() % 2 == 0)
    stats.median =
        0.5 * (stats.median + *std::max_element(errors.begin(), errors.begin() + std::ptrdiff_t(mid)));
  return stats;
}

MeshViewCoverage mesh_view_coverage(const Scene& scene) {
  MeshViewCoverage c;
  const std::size_t n = scene.mesh.num_faces();
  if (n == 0 || scene.views.empty()) return c;
  constexpr std::size_t kMaxFaces = 20000;
  const std::size_t step = (n + kMaxFaces - 1) / kMaxFaces;
  for (std::size_t f = 0; f < n; f += step) {
    const Face& face = scene.mesh.faces[f];
    const Vec3 centroid =
        (scene.mesh.vertices[std::size_t(face[0])] + scene.mesh.vertices[std::size_t(face[1])] +
         scene.mesh.vertices[std::size_t(face[2])]) /
        3.0;
    ++c.faces_checked;
    for (const View& v : scene.views) {
      Vec2 px;
      if (v.camera.project(centroid, &px) && v.camera.in_image(px)) {
        ++c.faces_in_view;
        break;
      }
    }
  }
  return c;
}

std::string mesh_frame_warning(const Scene& scene) {
  const MeshViewCoverage c = mesh_view_coverage(scene);
  if (c.faces_checked == 0 || c.share() >= 0.5) return {};
  const int percent = int(100.0 * c.share());
  return "only " + std::to_string(percent) + "% of the mesh's faces (" + std::to_string(c.faces_in_view) +
         " of " + std::to_string(c.faces_checked) +
         " checked) lie inside any camera's view: the mesh is probably in another coordinate "
         "frame than the cameras (exported from another model or chunk, or in a projected CRS)";
}

}  // namespace meshnbv
