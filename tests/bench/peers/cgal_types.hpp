#pragma once
// CGAL's kernel as kew_peers_bench uses it, and the traits that sort indices into a
// vector of points along a space-filling curve (the first period's Hilbert order, the
// CGAL baseline's insertion order).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/property_map.h>

namespace kew::bench::peers::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPoint = Kernel::Point_2;
using SortTraits = CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::Pointer_property_map<CgalPoint>::type>;

}  // namespace kew::bench::peers::cgal
