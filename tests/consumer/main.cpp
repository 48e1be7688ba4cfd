// A program that knows MeshNBV only through find_package(meshnbv).
#include <meshnbv/camera.h>

#include <cstdio>

int main() {
  auto cam = meshnbv::PinholeCamera::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 500, 500, 319.5,
                                             239.5, 640, 480);
  meshnbv::Vec2 px;
  if (!cam.project({0, 0, 0}, &px)) return 1;
  std::printf("%.3f %.3f\n", px.x(), px.y());
  return (std::abs(px.x() - 319.5) < 1e-9 && std::abs(px.y() - 239.5) < 1e-9) ? 0 : 1;
}
