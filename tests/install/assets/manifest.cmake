# The packing step of tests/install/assets: one line per baked file, its SHA-256.
set(text "")
foreach(f IN LISTS FILES)
  file(SHA256 "${f}" hash)
  get_filename_component(name "${f}" NAME)
  string(APPEND text "${name} ${hash}\n")
endforeach()
file(WRITE "${OUT}" "${text}")
