# Run as a script (cmake -DOUTPUT=... -DSOURCES="a;b" -P EmbedKernels.cmake): writes a C++ file
# holding each kernel source file's text, looked up by file name (kernel_registry below).
set(body "")
foreach(path IN LISTS SOURCES)
  get_filename_component(name ${path} NAME)
  file(READ ${path} text)
  string(APPEND body "    {\"${name}\", R\"dtcl(${text})dtcl\"},\n")
endforeach()
file(WRITE ${OUTPUT}.tmp "// Generated from cl/ by cmake/EmbedKernels.cmake: do not edit.
#include <map>
#include <string>

namespace depthtrack::compute {
const std::map<std::string, std::string>& kernel_registry() {
  static const std::map<std::string, std::string> files = {
${body}  };
  return files;
}
}  // namespace depthtrack::compute
")
# Only touch the output when it changed, so unrelated builds do not recompile it.
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUTPUT}.tmp)
