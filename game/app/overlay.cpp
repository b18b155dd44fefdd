#include "game/app/overlay.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "game/app/controls.h"

namespace rtrt {

Overlay::Overlay(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains the window's own callbacks
    ImGui_ImplOpenGL3_Init("#version 330 core");
}

Overlay::~Overlay() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

bool Overlay::WantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Overlay::WantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

void Overlay::Draw(OverlayModel& m) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (m.show) {
        ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.75f);
        ImGui::Begin("rtrt", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        const std::vector<float> history(m.frameMs.begin(), m.frameMs.end());
        float mean = 0.0f;
        for (float v : history) mean += v;
        mean = history.empty() ? 0.0f : mean / float(history.size());
        ImGui::Text("%s", m.scene.c_str());
        ImGui::Text("%.1f FPS  %.2f ms (mean of %zu)%s", mean > 0 ? 1000.0f / mean : 0.0f, mean,
                    history.size(), m.paused ? "  PAUSED" : "");
        const float top =
            history.empty() ? 1.0f : 1.25f * *std::max_element(history.begin(), history.end());
        // The graph takes at most a third of a small window's width, and says its scale.
        const float width = std::clamp(ImGui::GetIO().DisplaySize.x / 3.0f, 120.0f, 320.0f);
        char scale[64];
        std::snprintf(scale, sizeof(scale), "frame ms, 0 to %.1f", top);
        ImGui::PlotLines("##frame", history.data(), int(history.size()), 0, scale, 0.0f, top,
                         ImVec2(width, 0.2f * width + 6.0f));
        ImGui::Text("simulate %.3f  extract %.3f  upload %.3f", m.times.simulate, m.times.extract,
                    m.times.upload);
        if (m.times.deformed > 0)
            ImGui::Text("deform %.3f  BLAS %.3f ms (%u deforming, %u rebuilt)", m.times.deform,
                        m.times.blas, m.times.deformed, m.times.blasRebuilt);
        ImGui::Text("TLAS %.3f  trace %.3f  display %.3f ms", m.times.tlas, m.times.trace,
                    m.times.display);
        for (size_t g = 0; g < m.times.gpuTrace.size(); ++g)
            ImGui::Text("GPU %zu: trace %.3f ms, %u rows", g, m.times.gpuTrace[g],
                        m.times.gpuRows[g]);
        ImGui::Text("present %.3f  draw %.3f  overlay %.3f  swap %.3f ms", m.times.present,
                    m.times.draw, m.times.overlay, m.times.swap);
        ImGui::Text("instances %llu  triangles %llu", (unsigned long long)m.instances,
                    (unsigned long long)m.triangles);
        ImGui::Text("rays/frame %.2f M  TLAS nodes %llu", double(m.rays) * 1e-6,
                    (unsigned long long)m.tlasNodes);
        ImGui::Text("time scale %.2fx  %s", m.timeScale, m.display.c_str());
        if (!m.selected.empty()) ImGui::Text("picked: %s", m.selected.c_str());
        ImGui::Separator();
        ImGui::Checkbox("shadows", &m.shadows);
        ImGui::SameLine();
        ImGui::Checkbox("reflection", &m.reflection);
        ImGui::SameLine();
        ImGui::Checkbox("refraction", &m.refraction);
        ImGui::SliderInt("max depth", &m.maxDepth, 1, 8);
        const char* views[] = {"shaded", "normals", "depth", "heatmap"};
        ImGui::Combo("view", &m.view, views, 4);
        ImGui::SliderFloat("exposure (EV)", &m.exposureEv, -10.0f, 10.0f, "%.1f");
        const char* toneMaps[] = {"clamp", "PBR Neutral", "ACES"};
        ImGui::Combo("tone map", &m.toneMap, toneMaps, 3);
        ImGui::Checkbox("sRGB output (linear scene colours)", &m.srgb);
        int backend = m.useCuda ? 1 : 0;
        ImGui::RadioButton("CPU", &backend, 0);
        if (m.cudaAvailable) {
            ImGui::SameLine();
            ImGui::RadioButton("CUDA", &backend, 1);
        }
        m.useCuda = backend == 1;
        ImGui::Text("%s back end, GL: %s", m.backend.c_str(), m.glRenderer.c_str());
        ImGui::Checkbox("help (F1)", &m.showHelp);
        ImGui::End();
    }
    if (m.showHelp) {
        ImGui::SetNextWindowPos(ImVec2(360, 10), ImGuiCond_FirstUseEver);
        ImGui::Begin("controls", &m.showHelp, ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::TextUnformatted(kMouseHelp);
        ImGui::Separator();
        for (const Control& c : Controls()) ImGui::Text("%-9s %s", c.keyName, c.what);
        ImGui::End();
    }
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace rtrt
