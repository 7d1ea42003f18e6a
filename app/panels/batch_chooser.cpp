// The batch chooser above Statistics, Heat map, Recursion and Traversal: which batch of the
// first pass they analyse (ViewerState::batch). Any batch but the camera rays is recorded by
// the analysis job, the same pixel followed through each.
#include <imgui.h>

#include <algorithm>

#include "panels.h"

namespace edacrt::app {
namespace {

std::string batch_help(BatchId b) {
    switch (b.kind) {
        case BatchId::Kind::camera:
            return "the camera rays, one per pixel (the render's own statistics)";
        case BatchId::Kind::bounce:
            return "the closest-hit rays of the paths' bounce " + std::to_string(b.bounce) +
                   " (incoherent: where sampled alpha and filter skipping decide the most)";
        case BatchId::Kind::shadow:
            return "the any-hit shadow rays towards the emitters from the hits of " +
                   (b.bounce == 0 ? std::string("the camera rays")
                                  : "bounce " + std::to_string(b.bounce));
        case BatchId::Kind::ao:
            return "the any-hit ambient-occlusion rays, ao-samples per camera hit";
    }
    return "";
}

void choose(ViewerState& s, BatchId b) {
    if (b == s.batch) return;
    s.batch = b;
    s.analysis_requested = true;
}

}  // namespace

void draw_batch_chooser(ViewerState& s) {
    const std::vector<BatchId> batches = pass_batches(s.submitted.settings);
    const auto at = std::find(batches.begin(), batches.end(), s.batch);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    if (ImGui::BeginCombo("##batch", batch_name(s.batch).c_str())) {
        for (BatchId b : batches) {
            if (ImGui::Selectable(batch_name(b).c_str(), b == s.batch)) choose(s, b);
            if (ImGui::IsItemHovered()) wrapped_tooltip(batch_help(b));
        }
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
        wrapped_tooltip("the batch these tabs analyse, of the first pass (1 sample per pixel): " +
                        batch_help(s.batch));
    report_item(s, "Analysis/batch");
    // The batch before and after, in the order the pass traces them: a pixel's path, step
    // by step, in the traversal debugger.
    ImGui::SameLine();
    if (ImGui::ArrowButton("##batch-", ImGuiDir_Left) && at != batches.end() &&
        at != batches.begin())
        choose(s, *(at - 1));
    ImGui::SameLine();
    if (ImGui::ArrowButton("##batch+", ImGuiDir_Right) && at != batches.end() &&
        at + 1 != batches.end())
        choose(s, *(at + 1));
    ImGui::SameLine();
    if (at == batches.end()) {
        try {
            check_batch(s.batch, s.submitted.settings);
        } catch (const std::exception& e) {
            error_text(s, "Analysis/batch error", e.what());
            return;
        }
    }
    if (s.batch == BatchId{}) {
        ImGui::TextDisabled("batch");
        return;
    }
    const Analysis* a = s.analysis.get();
    if (s.analysis_running || s.analysis_requested)
        ImGui::TextDisabled("recording...");
    else if (a && a->batch == s.batch && !a->error.empty())
        error_text(s, "Analysis/batch error", a->error);
    else if (a && a->detail && a->batch == s.batch)
        ImGui::TextDisabled("%zu rays%s", a->detail->rays.size(),
                            s.analysis_stale ? " (stale)" : "");
    else
        ImGui::TextDisabled("batch");
}

}  // namespace edacrt::app
