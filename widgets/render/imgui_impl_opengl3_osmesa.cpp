// Dear ImGui's OpenGL3 backend, compiled against GL prototypes resolved from
// libOSMesa. The prebuilt backend in libimgui.a loads GL through its own loader,
// which finds nothing in an OSMesa context.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "imgui_impl_opengl3.cpp"  // NOLINT(bugprone-suspicious-include): the backend source
