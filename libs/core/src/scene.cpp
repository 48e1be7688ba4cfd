#include "meshnbv/scene.h"

#include "meshnbv/error.h"

namespace meshnbv {

std::shared_ptr<const Image> Scene::image(std::size_t i) const {
  if (i >= views.size()) throw Error("view index " + std::to_string(i) + " out of range");
  const View& view = views[i];
  if (!view.has_image()) throw Error("view '" + view.label + "' has no image");
  auto img = images->get(view.image_path);
  if (img->width() != view.camera.width || img->height() != view.camera.height)
    throw Error("image is " + std::to_string(img->width()) + "x" + std::to_string(img->height()) +
                    " but its camera says " + std::to_string(view.camera.width) + "x" +
                    std::to_string(view.camera.height),
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
  for (const auto& v : views) v.camera.check("view '" + v.label + "'");
}

}  // namespace meshnbv
