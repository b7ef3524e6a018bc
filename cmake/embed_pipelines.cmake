# Generates builtin_pipelines.cpp from pipelines/*.json: the built-in pipelines have one source,
# the JSON files a user can copy and edit. Run at build time whenever a JSON file changes.
file(GLOB files "${SRC_DIR}/*.json")
list(SORT files)
set(body "")
foreach(f ${files})
  get_filename_component(name "${f}" NAME_WE)
  file(READ "${f}" text)
  string(APPEND body "      {\"${name}\", R\"tandemjson(${text})tandemjson\"},\n")
endforeach()
file(WRITE "${OUT}.tmp" "// Generated from pipelines/*.json by cmake/embed_pipelines.cmake; do not edit.\n#include <map>\n#include <string>\n\nnamespace tandem {\n\nconst std::map<std::string, std::string>& builtinPipelineSources() {\n  static const std::map<std::string, std::string> b = {\n${body}  };\n  return b;\n}\n\n}  // namespace tandem\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUT}.tmp" "${OUT}")
