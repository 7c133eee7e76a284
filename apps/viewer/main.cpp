// mvcl-viewer: open a layered model, stack and drag lenses over it, look inside in real time.
// A thin shell, like Dear ImGui's examples: GLFW events go to the controller, the render
// session's image goes to a texture, and the panels are drawn from the framework's state.

#include "Viewer.h"
#include "ViewerOptions.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <cstdio>

int main(int argc, char **argv) {
    mvcl::viewer::ViewerOptions options;
    if (const int exitCode = mvcl::viewer::parseViewerOptions(argc, argv, options); exitCode >= 0) return exitCode;

    glfwSetErrorCallback([](int code, const char *text) { std::fprintf(stderr, "mvcl-viewer: GLFW %d: %s\n", code, text); });
    if (!glfwInit()) return 4;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    GLFWwindow *window = glfwCreateWindow(options.width, options.height, "mvcl-viewer", nullptr, nullptr);
    if (!window) {
        std::fprintf(stderr, "mvcl-viewer: no OpenGL 3.3 core window could be opened\n");
        glfwTerminate();
        return 4;
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(options.script ? 0 : 1); // scripts run as fast as frames can be drawn

    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // the layout is fixed; no imgui.ini in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    int exitCode = 0;
    {
        mvcl::viewer::Viewer viewer(window, options);
        while (!glfwWindowShouldClose(window) && !viewer.wantsToQuit()) {
            viewer.pollEvents();
            viewer.update();
            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            viewer.drawUi();
            ImGui::Render();
            int width, height;
            glfwGetFramebufferSize(window, &width, &height);
            glViewport(0, 0, width, height);
            glClearColor(0.08f, 0.08f, 0.09f, 1.f);
            glClear(GL_COLOR_BUFFER_BIT);
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            viewer.frameDrawn();
            glfwSwapBuffers(window);
        }
        exitCode = viewer.exitCode();
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return exitCode;
}
