# The library graph of docs/libraries.dot: kew's libraries and the two external libraries
# whose reach matters (CGAL only in kew_geometry, GeographicLib through kew_geo); no
# executables, tests or warning settings. Made in a configured build tree:
#   cp cmake/CMakeGraphVizOptions.cmake build/ && cmake --graphviz=build/graph/kew.dot build
set(GRAPHVIZ_GRAPH_NAME "kew_libraries")
set(GRAPHVIZ_EXECUTABLES FALSE)
set(GRAPHVIZ_GENERATE_PER_TARGET FALSE)
set(GRAPHVIZ_GENERATE_DEPENDERS FALSE)
set(GRAPHVIZ_IGNORE_TARGETS "^kew_warnings$" "^kew_test_" "^kew_revision$" "^fmt::" "^Threads::" "^Boost::"
    "^spdlog::" "^simdjson::" "^ZLIB::" "^tomlplusplus::" "^PkgConfig::" "^GTest::" "^benchmark::" "^CLI11::"
    "^CGAL::CGAL_Core" "^/usr/lib/" "^-")
