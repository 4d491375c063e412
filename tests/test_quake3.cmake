# Embree: the "is the segment to the light blocked?" oracle of the shadow-volume law on real maps.
find_package(embree 3 REQUIRED)
target_link_libraries(${name} PRIVATE embree)
