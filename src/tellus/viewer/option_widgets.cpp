#include "tellus/viewer/option_widgets.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

#include <fmt/format.h>
#include <imgui.h>

namespace tellus {
namespace {

// The slider's text: the value with its unit ("%.3g px"), or "auto" for the 0 that asks for the
// automatic default (the label column is narrow: units and notes go into the slider).
std::string formatOf(const RendererOption& option, bool isZero) {
  if (option.autoDefault && isZero) return "auto";
  const std::string number = option.kind == OptionKind::Integer ? "%d" : "%.3g";
  return option.unit.empty() ? number : number + " " + option.unit;
}

// The slider's range: the panel's where the schema gives one, else the accepted range; from 0
// when 0 asks for the automatic default.
std::pair<double, double> sliderRange(const RendererOption& option) {
  const double low = option.autoDefault ? 0.0 : option.panelMin != 0.0 ? option.panelMin : option.min;
  const double high = option.panelMax != 0.0 ? option.panelMax : option.max;
  return {low, high};
}

ImGuiSliderFlags scaleOf(double low, double high) {
  return low > 0.0 && high / low >= 100.0 ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None;
}

}  // namespace

bool drawOptionWidgets(const OptionSchema& schema, std::any& options) {
  bool remake = false;
  for (const RendererOption& option : schema.options) {
    if (!option.inPanel) continue;
    const std::string& label = option.label;
    ImGui::PushID(option.flag.c_str());
    bool committed = false;  // a change the renderer must be remade for (unless live)
    const OptionValue value = option.get(options);
    if (!option.panelSteps.empty()) {
      const std::string current = formatOptionValue(value);
      if (ImGui::BeginCombo(label.c_str(), current.c_str())) {
        for (double step : option.panelSteps) {
          const OptionValue stepValue = option.kind == OptionKind::Integer
                                            ? OptionValue(std::int64_t(step))
                                            : OptionValue(step);
          const std::string text = formatOptionValue(stepValue);
          if (ImGui::Selectable(text.c_str(), text == current) && text != current) {
            option.set(options, stepValue);
            committed = true;
          }
        }
        ImGui::EndCombo();
      }
    } else if (option.kind == OptionKind::Integer) {
      const auto [low, high] = sliderRange(option);
      int shown = int(std::clamp<std::int64_t>(std::get<std::int64_t>(value), std::int64_t(low),
                                               std::int64_t(high)));
      const std::string format = formatOf(option, shown == 0);
      if (ImGui::SliderInt(label.c_str(), &shown, int(low), int(high), format.c_str(),
                           scaleOf(low, high)))
        option.set(options, std::int64_t(shown));
      committed = ImGui::IsItemDeactivatedAfterEdit();
    } else if (option.kind == OptionKind::Real) {
      const auto [low, high] = sliderRange(option);
      float shown = float(std::get<double>(value));
      const std::string format = formatOf(option, shown == 0.0f);
      if (ImGui::SliderFloat(label.c_str(), &shown, float(low), float(high), format.c_str(),
                             scaleOf(low, high)))
        option.set(options, double(shown));
      committed = ImGui::IsItemDeactivatedAfterEdit();
    } else if (option.kind == OptionKind::Flag) {
      bool on = std::get<bool>(value);
      if (ImGui::Checkbox(label.c_str(), &on)) {
        option.set(options, on);
        committed = true;
      }
    } else if (option.kind == OptionKind::Choice) {
      const std::string& current = std::get<std::string>(value);
      if (ImGui::BeginCombo(label.c_str(), current.c_str())) {
        for (const std::string& choice : option.choices) {
          if (ImGui::Selectable(choice.c_str(), choice == current) && choice != current) {
            option.set(options, choice);
            committed = true;
          }
        }
        ImGui::EndCombo();
      }
    } else {
      // Files and feature lists are set on the command line; the panel shows them.
      const std::string text = formatOptionValue(value);
      if (!text.empty()) ImGui::TextWrapped("%s: %s", option.label.c_str(), text.c_str());
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)", option.help.c_str(), option.flag.c_str());
    remake |= committed && !option.live;
    ImGui::PopID();
  }
  return remake;
}

}  // namespace tellus
