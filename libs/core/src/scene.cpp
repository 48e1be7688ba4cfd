#include "meshnbv/scene.h"

#include "meshnbv/error.h"

namespace meshnbv {
namespace {

void check_one_source(const View& view) {
  if (!view.image_path.empty() && view.pixels)
    throw Error("has both an image file and an in-memory image; set one (image_path or pixels)",
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

std::shared_ptr<const Image> Scene::image(std::size_t i) const {
  if (i >= views.size()) throw Error("view index " + std::to_string(i) + " out of range");
  const View& view = views[i];
  if (!view.has_image()) throw Error("view '" + view.label + "' has no image");
  check_one_source(view);
  auto img = view.pixels ? view.pixels : images->get(view.image_path);
  if (img->width() != view.camera.width || img->height() != view.camera.height)
    throw Error((view.pixels ? "in-memory image is " : "image is ") + std::to_string(img->width()) +
                    "x" + std::to_string(img->height()) + " but its camera says " +
                    std::to_string(view.camera.width) + "x" + std::to_string(view.camera.height),
                view.image_path, -1, "view '" + view.label + "'");
  return img;
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

}  // namespace meshnbv
