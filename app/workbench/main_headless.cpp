#include <iostream>

#include "osmesa_renderer.h"
#include "workbench.h"

int main() {
  tactile::OffscreenRenderer renderer(1280, 800);
  tactile::WorkbenchState state;
  renderer.new_frame();
  tactile::draw_workbench(state);
  tactile::write_png("screenshot.png", renderer.render());
  return 0;
}
