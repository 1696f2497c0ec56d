// The workbench in a GLFW window. Without a display, or with --headless, it hands
// over to tactile-workbench-headless (OSMesa must not share a binary with libGL).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "frame_loop.h"
#include "tactile/widgets/image.h"
#include "workbench.h"
#include "workbench_args.h"

namespace {

std::filesystem::path program_folder() {
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path(".") : self.parent_path();
}

// Replaces this process with the headless workbench, adding `extra` arguments.
int run_headless(int argc, char** argv, const std::vector<std::string>& extra) {
  const std::string program = (program_folder() / "tactile-workbench-headless").string();
  std::vector<std::string> arguments = {program};
  for (int k = 1; k < argc; ++k)
    if (std::string(argv[k]) != "--headless") arguments.emplace_back(argv[k]);
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  std::vector<char*> pointers;
  for (std::string& argument : arguments) pointers.push_back(argument.data());
  pointers.push_back(nullptr);
  execv(program.c_str(), pointers.data());
  std::cerr << "tactile-workbench: cannot start " << program << "\n";
  return 1;
}

tactile::Image read_framebuffer(int width, int height) {
  tactile::Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(static_cast<size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  image.flip_vertically();
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  tactile::WorkbenchArgs args;
  if (auto code = tactile::parse_workbench_args(argc, argv, args)) return *code;
  if (args.headless) return run_headless(argc, argv, {});

  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  const bool has_display = (display && *display) || (wayland && *wayland);
  if (!has_display || !glfwInit()) {
    std::vector<std::string> extra;
    std::string target = args.screenshot;
    if (target.empty() && args.script.empty()) {
      target = (program_folder().parent_path() / "screenshot.png").string();
      extra = {"--screenshot", target};
    }
    if (args.script.empty())
      std::cerr << "tactile-workbench: no display; rendering the main window headless to " << target
                << "\n";
    return run_headless(argc, argv, extra);
  }

  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  GLFWwindow* window =
      glfwCreateWindow(args.width, args.height, "Tactile Workbench", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    std::cerr << "tactile-workbench: cannot open an OpenGL 3.3 window; try --headless\n";
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is computed each frame
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");

  int exit_code = 0;
  try {
    tactile::Workbench workbench(args.options);
    if (!workbench.error().empty()) std::cerr << "tactile-workbench: " << workbench.error() << "\n";
    tactile::FrameLoop loop(workbench, args);
    double last = glfwGetTime();
    while (!glfwWindowShouldClose(window)) {
      glfwPollEvents();
      const double now = glfwGetTime();
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      const double seconds = loop.begin(now - last);
      ImGui::NewFrame();
      workbench.frame(seconds);
      last = now;
      ImGui::Render();
      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      glViewport(0, 0, width, height);
      glClearColor(0.09f, 0.09f, 0.1f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      if (!loop.end([&] { return read_framebuffer(width, height); })) break;
      glfwSwapBuffers(window);
    }
    exit_code = loop.exit_code();
  } catch (const std::exception& error) {
    std::cerr << "tactile-workbench: " << error.what() << "\n";
    exit_code = 1;
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return exit_code;
}
