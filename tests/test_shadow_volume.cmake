# Embree: the independent "is the segment blocked?" reference of the shadow-volume laws.
find_package(embree 3 REQUIRED)
target_link_libraries(${name} PRIVATE embree)
