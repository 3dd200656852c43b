cmake_minimum_required(VERSION 3.25)  # script mode: IN_LIST and the other policies of the build
# Turns OpenCL sources into a C++ file of raw strings, inlining
# `#include "common/…"` lines (each header once) so the binary runs from any
# directory. Invoked by kernels/CMakeLists.txt as a build step:
#   cmake -DKERNEL_DIR=… -DOUTPUT=… -P embed_kernels.cmake
#
# The programs are found, not listed: every .cl under KERNEL_DIR that no
# other .cl includes is a program named after its file (kernels/vbd/vbd.cl
# is "vbd"), except the fused dispatcher (device/dispatch.cl), which is
# appended to every program that declares task functions, under `#if
# ATS_FUSED` (the fused executor builds with -DATS_FUSED=1): it needs OpenCL
# C 2.0 atomics, which an events-only device such as an NVIDIA GPU (OpenCL C
# 3.0 without the atomic-scope features) does not compile. A new method's
# kernels/<method>/<method>.cl is thus embedded without naming it here.
#
# A program's task functions (`ATS_TASK void name(int i, …)`, common/task.h)
# are its kernels' one declaration. For each, this script generates
#   - the events executor's thin kernel ats_k_<name>(…, int first, int count),
#   - a case of ats_run_range(), which the fused dispatcher
#     (device/dispatch.cl, appended after it) calls over a work-group's share,
#   - the signature the host checks launches against (program_tasks()).
function(inline_includes path out_var seen_var)
  # file(READ), not file(STRINGS): C source is full of ';', CMake's list separator.
  file(READ "${path}" content)
  set(seen ${${seen_var}})
  string(REGEX MATCHALL "#[ \t]*include[ \t]*\"[^\"]+\"" directives "${content}")
  foreach(directive IN LISTS directives)
    string(REGEX REPLACE "#[ \t]*include[ \t]*\"([^\"]+)\"" "\\1" relative "${directive}")
    set(inc "${KERNEL_DIR}/${relative}")
    if(NOT EXISTS "${inc}")
      message(FATAL_ERROR "${path}: included file ${relative} not found under ${KERNEL_DIR}")
    endif()
    set(sub "")
    list(FIND seen "${inc}" found)
    if(found EQUAL -1)
      list(APPEND seen "${inc}")
      inline_includes("${inc}" sub seen)
    endif()
    string(REPLACE "${directive}" "${sub}" content "${content}")
  endforeach()
  set(${out_var} "${content}" PARENT_SCOPE)
  set(${seen_var} ${seen} PARENT_SCOPE)
endfunction()

function(strip text out_var)
  string(REGEX REPLACE "[ \t\r\n]+" " " text "${text}")
  string(STRIP "${text}" text)
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# Appends to `cl_var` the thin kernels and ats_run_range() of the task
# functions in `source`, and to `table_var` their C++ signature rows; sets
# `count_var` to how many there are.
function(generate_tasks program source cl_var table_var count_var)
  set(ident "[A-Za-z_][A-Za-z0-9_]*")
  string(REGEX MATCHALL "ATS_TASK[ \t\r\n]+void[ \t\r\n]+${ident}[ \t\r\n]*\\([^)]*\\)[ \t\r\n]*{" decls "${source}")
  set(kernels "")
  set(cases "")
  set(rows "")
  set(index 0)
  foreach(decl IN LISTS decls)
    string(REGEX REPLACE "^ATS_TASK[ \t\r\n]+void[ \t\r\n]+(${ident}).*$" "\\1" name "${decl}")
    string(REGEX REPLACE "^[^(]*\\(([^)]*)\\).*$" "\\1" params "${decl}")
    strip("${params}" params)
    string(REPLACE "," ";" plist "${params}")
    list(POP_FRONT plist element)
    strip("${element}" element)
    if(NOT element MATCHES "^int ${ident}$")
      message(FATAL_ERROR "program ${program}: task function ${name} must take the element index 'int i' first, "
                          "not '${element}'")
    endif()
    set(decl_list "")   # parameters as declared, for the thin kernel and messages
    set(names "")
    set(kinds "")
    set(access "")
    set(unpack "")
    set(slot 0)
    foreach(p IN LISTS plist)
      strip("${p}" p)
      string(REGEX MATCH "${ident}$" pname "${p}")
      string(REGEX REPLACE "${ident}$" "" ptype "${p}")
      strip("${ptype}" ptype)
      # The dispatcher unpacks the parameters from its argument array `a`
      # beside the element index `i`: a parameter of either name would
      # shadow them and break the program build far from its cause.
      if(pname STREQUAL "a" OR pname STREQUAL "i")
        message(FATAL_ERROR "program ${program}: task function ${name} has a parameter named '${pname}', "
                            "which the fused dispatcher uses itself; rename it")
      endif()
      if(ptype MATCHES "\\*")
        string(APPEND kinds "b")
        if(ptype MATCHES "const")
          string(APPEND access "r")
        else()
          string(APPEND access "w")
        endif()
        string(APPEND unpack "      ${ptype} ${pname} = (${ptype})a[${slot}];\n")
      elseif(ptype STREQUAL "float")
        string(APPEND kinds "f")
        string(APPEND access "-")
        string(APPEND unpack "      const float ${pname} = as_float((uint)a[${slot}]);\n")
      elseif(ptype STREQUAL "int")
        string(APPEND kinds "i")
        string(APPEND access "-")
        string(APPEND unpack "      const int ${pname} = (int)a[${slot}];\n")
      else()
        message(FATAL_ERROR "program ${program}: task function ${name}: parameter '${p}' is neither a __global "
                            "pointer, an int nor a float")
      endif()
      list(APPEND decl_list "${p}")
      list(APPEND names "${pname}")
      math(EXPR slot "${slot} + 1")
    endforeach()
    list(JOIN decl_list ", " decl_text)
    list(JOIN names ", " name_text)
    set(sep "")
    if(NOT name_text STREQUAL "")
      set(sep ", ")
    endif()
    string(APPEND kernels "__kernel void ats_k_${name}(${decl_text}${sep}int ats_first, int ats_count) {\n"
                          "  const int ats_k = get_global_id(0);\n"
                          "  if (ats_k < ats_count) ${name}(ats_first + ats_k${sep}${name_text});\n}\n")
    string(APPEND cases "    case ${index}: {\n${unpack}"
                        "      for (int ats_i = begin; ats_i < end; ++ats_i) ${name}(ats_i${sep}${name_text});\n"
                        "      break;\n    }\n")
    string(APPEND rows "    {\"${name}\", ${index}, \"${kinds}\", \"${access}\", \"${decl_text}\"},\n")
    math(EXPR index "${index} + 1")
  endforeach()
  if(index GREATER 0)
    set(${cl_var} "${${cl_var}}\n/* Generated by kernels/embed_kernels.cmake from the task functions above. */\n${kernels}\nstatic void ats_run_range(int function, __global const ulong* a, int begin, int end) {\n  switch (function) {\n${cases}    default:\n      break;\n  }\n}\n" PARENT_SCOPE)
  endif()
  set(${table_var} "${rows}" PARENT_SCOPE)
  set(${count_var} ${index} PARENT_SCOPE)
endfunction()

set(dispatcher_path "device/dispatch.cl")
file(GLOB_RECURSE cl_files RELATIVE "${KERNEL_DIR}" "${KERNEL_DIR}/*.cl")
set(included "")
foreach(path IN LISTS cl_files)
  file(READ "${KERNEL_DIR}/${path}" content)
  string(REGEX MATCHALL "#[ \t]*include[ \t]*\"[^\"]+\\.cl\"" directives "${content}")
  foreach(directive IN LISTS directives)
    string(REGEX REPLACE "#[ \t]*include[ \t]*\"([^\"]+)\"" "\\1" relative "${directive}")
    list(APPEND included "${relative}")
  endforeach()
endforeach()
set(programs "")
set(program_names "")
foreach(path IN LISTS cl_files)
  if(path IN_LIST included OR path STREQUAL dispatcher_path)
    continue()
  endif()
  get_filename_component(name "${path}" NAME_WE)
  if(name IN_LIST program_names)
    message(FATAL_ERROR "two OpenCL programs are named '${name}' (${path} and another); rename one file")
  endif()
  list(APPEND program_names "${name}")
  list(APPEND programs "${name}=${path}")
endforeach()

set(body "// Generated by kernels/embed_kernels.cmake — do not edit.\n#include \"kernels/embedded_programs.hpp\"\n\nnamespace atssim::kernels {\n\nnamespace {\n")
set(table "")
set(task_table "")
foreach(entry IN LISTS programs)
  string(REPLACE "=" ";" pair "${entry}")
  list(GET pair 0 name)
  list(GET pair 1 path)
  set(seen "")
  inline_includes("${KERNEL_DIR}/${path}" source seen)
  set(generated "")
  generate_tasks("${name}" "${source}" generated rows task_count)
  if(task_count GREATER 0)
    inline_includes("${KERNEL_DIR}/${dispatcher_path}" dispatcher seen)
    string(APPEND source "${generated}\n#if ATS_FUSED\n${dispatcher}\n#endif\n")
    string(APPEND body "const TaskSignature k_${name}_tasks[] = {\n${rows}};\n")
    string(APPEND task_table "  if (name == \"${name}\") return k_${name}_tasks;\n")
  endif()
  string(APPEND body "const char* const k_${name} = R\"atssimcl(${source})atssimcl\";\n")
  string(APPEND table "  if (name == \"${name}\") return k_${name};\n")
endforeach()
string(APPEND body "}  // namespace\n\nconst char* program_source(std::string_view name) {\n${table}  return nullptr;\n}\n\n")
string(APPEND body "std::span<const TaskSignature> program_tasks(std::string_view name) {\n${task_table}  return {};\n}\n\n}  // namespace atssim::kernels\n")
file(WRITE "${OUTPUT}.tmp" "${body}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
