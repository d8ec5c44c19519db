#pragma once
// The radius of the graph's nodes in scene units, shared by the nodes (graph_view.cpp) and the
// labels placed around them (graph_view_labels.cpp).

namespace archet::ui {

inline constexpr double kNodeRadius = 9;

}  // namespace archet::ui
