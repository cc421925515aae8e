#include <imgui.h>

#include <algorithm>
#include <system_error>

#include "ui/panel_fit.h"
#include "ui/ui.h"

namespace ui {

void showWorldPanel(WorldPanel& panel, bool* open) {
    panel.request = WorldPanel::Request::None;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.55f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(480, 0), ImGuiCond_Appearing);
    fitNextWindowToDisplay();
    if (!ImGui::Begin("Worlds", open, kPanelFlags)) {
        ImGui::End();
        return;
    }
    ImGui::TextWrapped("Folder: %s", panel.folder.c_str());
    ImGui::Text("Playing: %s", panel.current.empty() ? "(not saved)" : panel.current.c_str());
    ImGui::Separator();

    std::vector<std::filesystem::path> worlds;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(panel.folder, ec)) {
        // A recording's start world (NAME.mcscript.start.mcworld, .start.2.mcworld, ...) is the recording's, not a
        // world to play on: Worlds > Recordings plays it.
        if (entry.path().extension() == ".mcworld" &&
            entry.path().filename().string().find(".mcscript.start.") == std::string::npos)
            worlds.push_back(entry.path());
    }
    std::sort(worlds.begin(), worlds.end());
    if (worlds.empty()) ImGui::TextDisabled("No saved worlds yet.");
    for (const auto& w : worlds) {
        ImGui::PushID(w.c_str());
        ImGui::TextUnformatted(w.stem().c_str());
        ImGui::SameLine(260);
        const bool isCurrent = w.string() == panel.current;
        if (isCurrent) {
            ImGui::TextDisabled("playing");
        } else {
            if (ImGui::SmallButton("Load")) {
                panel.request = WorldPanel::Request::Load;
                panel.target = w;
            }
            ImGui::SameLine();
            if (ImGui::SmallButton("Delete")) {
                panel.pendingDelete = w;
                ImGui::OpenPopup("Delete world?");
            }
        }
        if (ImGui::BeginPopupModal("Delete world?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
            ImGui::Text("Delete %s for good?", panel.pendingDelete ? panel.pendingDelete->stem().c_str() : "");
            if (ImGui::Button("Delete")) {
                panel.request = WorldPanel::Request::Delete;
                panel.target = panel.pendingDelete.value_or(std::filesystem::path());
                panel.pendingDelete.reset();
                ImGui::CloseCurrentPopup();
            }
            ImGui::SameLine();
            // Esc is "Keep it": ImGui leaves a modal open on Esc, and the Worlds page stays under it.
            if (ImGui::Button("Keep it") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) {
                panel.pendingDelete.reset();
                ImGui::CloseCurrentPopup();
            }
            ImGui::EndPopup();
        }
        ImGui::PopID();
    }
    ImGui::Separator();
    ImGui::InputText("name", panel.newName, sizeof panel.newName);
    ImGui::InputScalar("seed", ImGuiDataType_U64, &panel.newSeed);
    ImGui::Checkbox("flat terrain", &panel.newFlat);
    if (ImGui::Button("Create and play")) {
        std::string name = panel.newName;
        // A file name, not a path: keep letters, digits, space, '-' and '_'.
        name.erase(std::remove_if(name.begin(), name.end(),
                                  [](char c) {
                                      return !(std::isalnum(static_cast<unsigned char>(c)) || c == ' ' || c == '-' ||
                                               c == '_');
                                  }),
                   name.end());
        if (name.empty()) name = "world";
        std::filesystem::path target = panel.folder / (name + ".mcworld");
        for (int n = 2; std::filesystem::exists(target, ec); ++n)
            target = panel.folder / (name + "-" + std::to_string(n) + ".mcworld");
        panel.request = WorldPanel::Request::Create;
        panel.target = target;
    }
    ImGui::SameLine(); // on the same row: the page keeps its height and its rows their places
    if (ImGui::Button("Recordings...")) panel.request = WorldPanel::Request::Recordings;
    if (!panel.status.empty()) ImGui::TextWrapped("%s", panel.status.c_str());
    ImGui::End();
}

void showRecordingsPanel(RecordingsPanel& panel, bool* open) {
    panel.play = false;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    // Its top at a fixed place and the list first: the rows stand where they do whatever the folder's name.
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.3f), ImGuiCond_Appearing, ImVec2(0.5f, 0.0f));
    fitNextWindowToDisplay();
    if (!ImGui::Begin("Recordings", open, kPanelFlags | ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::End();
        return;
    }
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 34.0f); // the window fits its content: wrap, do not widen
    struct Entry {
        std::filesystem::path path;
        std::filesystem::file_time_type written;
    };
    std::vector<Entry> recordings;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(panel.folder, ec)) {
        if (entry.path().extension() == ".mcscript") recordings.push_back({entry.path(), entry.last_write_time(ec)});
    }
    std::sort(recordings.begin(), recordings.end(), [](const Entry& a, const Entry& b) {
        return a.written != b.written ? a.written > b.written : a.path < b.path;
    });
    if (recordings.empty()) ImGui::TextDisabled("No recordings here yet.");
    for (const Entry& r : recordings) {
        ImGui::PushID(r.path.c_str());
        ImGui::TextUnformatted(r.path.stem().c_str());
        ImGui::SameLine(260);
        if (ImGui::SmallButton("Play")) {
            panel.play = true;
            panel.target = r.path;
        }
        ImGui::PopID();
    }
    ImGui::Separator();
    ImGui::TextWrapped("Folder: %s", panel.folder.c_str());
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("minecrappy --record %s/NAME.mcscript records one here.", panel.folder.c_str());
    ImGui::PopStyleColor();
    if (!panel.status.empty()) ImGui::TextWrapped("%s", panel.status.c_str());
    ImGui::PopTextWrapPos();
    ImGui::End();
}

} // namespace ui
