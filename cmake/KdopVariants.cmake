# kdop_add_variants(<target>
#     [SETS <name-or-path>...]          built-in set names (the stems of shader_templates/axis_sets/*.axes:
#                                       aabb ycocg dop16-asphalt dop16-grass dop22 dop32) or paths to .axes
#                                       files; default: every built-in set
#     [MODES <clip|varclip>...]         default: both
#     [NEIGHBORHOODS <n9|n5>...]        default: both
#     [FORMS <unrolled|loop>...]        default: unrolled; loop is the supplement's form, a baseline
#     [BASELINES]                       also the cost baselines gather-n9, gather-n5 and copy
#     [MANIFEST <file>]                 instead of the five above: exactly the variants a scene's manifest
#                                       lists (generator/manifest.h; its `set:` files are inputs too); the
#                                       resolve it records (kdop choose's), the header declares as
#                                       resolve_settings and the JSON holds as "resolve"
#     [NAMESPACE <ns>]                  C++ namespace of the registry; default: <target> made an identifier
#     [HEADER <file-name>]              default: <target>_kdop_variants.h
#     [PUBLIC]                          also give <target>'s users the header (for a library target)
#     [FUNCTIONS]                       also write each variant's includable function, <variant>.glsl,
#                                       <variant>.hlsl and <variant>.wgsl, into a folder for the project's own
#                                       shader build
#     [TARGET_ENV <vulkan1.0..1.3>]     the SPIR-V's target environment; default vulkan1.0
#     [STRIP_NAMES]                     drop OpName and OpMemberName from the SPIR-V, for shipping; by default
#                                       they are kept (as glslc keeps them) for debuggers and spirv-cross
#     [SHADERS <file>...]               the project's own shaders, compiled into the registry too (named after
#                                       their files without the extensions, with their reflected bindings and
#                                       stage): GLSL compute (.comp), vertex (.vert) or fragment (.frag), where
#                                       `#include "dop22-clip-n9.glsl"` gives them a selected variant's function,
#                                       and HLSL compute (.cs.hlsl), vertex (.vs.hlsl) or pixel (.ps.hlsl), where
#                                       `#include "dop22-clip-n9.hlsl"` does
#     [HLSL_ENTRY <name>]               the HLSL SHADERS' entry point (DXC's -E); default main
#     [SHADER_INCLUDE_DIRS <dir>...])   where the SHADERS' other includes are looked up (after their own folder)
#
# Generates, at build time, a header and source holding the variants' optimized SPIR-V and their
# registry (see core/include/kdop/variant.h), adds them to <target>, and lets <target>
# include the header by its file name. Beside the header, <header stem>.json holds the same
# reflection as JSON (docs/reflection.schema.json), for tools that do not read C++: the target's
# KDOP_REFLECTION_JSON property and ${<target>_KDOP_REFLECTION_JSON} in the caller's scope. Generation reruns when a user axis file, a shader or a file
# it includes, or kdop-gen (which embeds the built-in sets and templates) changes, and at no other
# time; files whose content did not change keep their time stamps, so nothing recompiles for them.
#
# With FUNCTIONS, the folder is the target's KDOP_FUNCTION_DIR property and <target>_KDOP_FUNCTION_DIR
# in the caller's scope; its files are outputs of the generation, so a custom command of the same
# folder that DEPENDS on one (${<target>_KDOP_FUNCTION_DIR}/dop22-clip-n9.glsl) runs after it.
include_guard(GLOBAL)

# The built-in sets are the axis files kdop-gen embeds; the list is read from that folder, not kept
# here, and inside the function, so it holds wherever kdop_add_variants() is called from. An
# installed package's config file names the installed copy first; in kdop's own tree it is here.
get_property(kdop_axis_set_dir_known GLOBAL PROPERTY KDOP_AXIS_SET_DIR SET)
if(NOT kdop_axis_set_dir_known)
  set_property(GLOBAL PROPERTY KDOP_AXIS_SET_DIR "${CMAKE_CURRENT_LIST_DIR}/../shader_templates/axis_sets")
endif()

# The extensions of the languages a variant's function is written in, read from the one list
# (generator/shader_languages.def; an installed package's config file names the installed copy).
get_property(kdop_languages_file_known GLOBAL PROPERTY KDOP_SHADER_LANGUAGES_FILE SET)
if(NOT kdop_languages_file_known)
  set_property(GLOBAL PROPERTY KDOP_SHADER_LANGUAGES_FILE "${CMAKE_CURRENT_LIST_DIR}/../generator/shader_languages.def")
endif()

# Sets <out_var> to those extensions, without the dot (glsl;hlsl;wgsl).
function(kdop_shader_language_extensions out_var)
  get_property(languages_file GLOBAL PROPERTY KDOP_SHADER_LANGUAGES_FILE)
  file(STRINGS "${languages_file}" lines REGEX "^KDOP_SHADER_LANGUAGE\\(")
  set(extensions)
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^KDOP_SHADER_LANGUAGE\\(([a-z0-9]+),.*" "\\1" extension "${line}")
    list(APPEND extensions "${extension}")
  endforeach()
  if(NOT extensions)
    message(FATAL_ERROR "kdop: ${languages_file} lists no shader language")
  endif()
  set(${out_var} "${extensions}" PARENT_SCOPE)
endfunction()

function(kdop_add_variants target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "PUBLIC;BASELINES;FUNCTIONS;STRIP_NAMES" "NAMESPACE;HEADER;TARGET_ENV;MANIFEST;HLSL_ENTRY"
                        "SETS;MODES;NEIGHBORHOODS;FORMS;SHADERS;SHADER_INCLUDE_DIRS")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "kdop_add_variants(${target}): unknown arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET ${target})
    message(FATAL_ERROR "kdop_add_variants(${target}): no such target")
  endif()
  if(NOT TARGET kdop::kdop-gen)
    message(FATAL_ERROR "kdop_add_variants(${target}): kdop::kdop-gen is not defined; use find_package(kdop) or add_subdirectory(kdop) first")
  endif()

  if(NOT ARG_NAMESPACE)
    string(MAKE_C_IDENTIFIER "${target}_kdop" ARG_NAMESPACE)
  endif()
  if(NOT ARG_HEADER)
    set(ARG_HEADER "${target}_kdop_variants.h")
  endif()
  get_filename_component(header_stem "${ARG_HEADER}" NAME_WE)
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/kdop_variants/${target}")
  set(header "${out_dir}/${ARG_HEADER}")
  set(source "${out_dir}/${header_stem}.cpp")
  set(json "${out_dir}/${header_stem}.json")
  # What kdop-gen would refuse at every build, refused once, here. C++23's keywords and alternative
  # tokens cannot name the namespace: the list generator/registry_writer.cpp refuses, kept here, in
  # the function, so it holds wherever the function is called from; a test keeps the two equal.
  set(cpp_keywords
      alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t char32_t class
      compl concept const consteval constexpr constinit const_cast continue co_await co_return co_yield decltype
      default delete do double dynamic_cast else enum explicit export extern false float for friend goto if inline
      int long mutable namespace new noexcept not not_eq nullptr operator or or_eq private protected public register
      reinterpret_cast requires return short signed sizeof static static_assert static_cast struct switch template
      this thread_local throw true try typedef typeid typename union unsigned using virtual void volatile wchar_t
      while xor xor_eq)
  if(header STREQUAL source)
    message(FATAL_ERROR "kdop_add_variants(${target}): HEADER ${ARG_HEADER} is also the registry's source (${header_stem}.cpp); name the header .h or .hpp")
  endif()
  if(ARG_HEADER MATCHES "[\"\\\\/]" OR NOT ARG_HEADER MATCHES "^[ -~]+$")
    message(FATAL_ERROR "kdop_add_variants(${target}): HEADER '${ARG_HEADER}' must be a file name that #include \"...\" can hold: printable ASCII without a quote, backslash or slash")
  endif()
  if(NOT ARG_NAMESPACE MATCHES "^[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*$")
    message(FATAL_ERROR "kdop_add_variants(${target}): NAMESPACE '${ARG_NAMESPACE}' is not a C++ namespace (identifiers separated by ::)")
  endif()
  string(REPLACE "::" ";" namespace_parts "${ARG_NAMESPACE}")
  foreach(part IN LISTS namespace_parts)
    if(part IN_LIST cpp_keywords)
      message(FATAL_ERROR "kdop_add_variants(${target}): NAMESPACE ${ARG_NAMESPACE} holds the C++ keyword '${part}', which cannot name a namespace")
    endif()
    if(part MATCHES "__" OR part MATCHES "^_[A-Z]")
      message(FATAL_ERROR "kdop_add_variants(${target}): NAMESPACE ${ARG_NAMESPACE} holds '${part}', a name reserved for the C++ implementation")
    endif()
  endforeach()

  if(DEFINED ARG_HLSL_ENTRY AND NOT ARG_HLSL_ENTRY MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
    message(FATAL_ERROR "kdop_add_variants(${target}): HLSL_ENTRY '${ARG_HLSL_ENTRY}' is not an HLSL function name")
  endif()

  get_property(axis_set_dir GLOBAL PROPERTY KDOP_AXIS_SET_DIR)
  file(GLOB builtin_files "${axis_set_dir}/*.axes")
  set(builtin_sets)
  foreach(file IN LISTS builtin_files)
    get_filename_component(name "${file}" NAME_WE)
    list(APPEND builtin_sets ${name})
  endforeach()

  # User axis files and manifests are inputs of their own; built-in sets live inside kdop-gen.
  set(arguments)
  set(depends kdop::kdop-gen)
  set(variant_names) # as kdop-gen names them, for the FUNCTIONS outputs
  if(ARG_MANIFEST)
    if(ARG_SETS OR ARG_MODES OR ARG_NEIGHBORHOODS OR ARG_FORMS OR ARG_BASELINES)
      message(FATAL_ERROR "kdop_add_variants(${target}): MANIFEST lists the variants; it excludes SETS, MODES, NEIGHBORHOODS, FORMS and BASELINES")
    endif()
    get_filename_component(manifest "${ARG_MANIFEST}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    if(NOT EXISTS "${manifest}")
      message(FATAL_ERROR "kdop_add_variants(${target}): MANIFEST ${manifest} does not exist")
    endif()
    list(APPEND arguments --manifest "${manifest}")
    list(APPEND depends "${manifest}")
    # Its `set:` files are inputs too, its other `key: value` lines the resolve it records (which
    # kdop-gen checks and declares in the header), and its other lines the variants' names (kdop-gen
    # checks them); reconfigure when it changes, in case they did.
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${manifest}")
    get_filename_component(manifest_dir "${manifest}" DIRECTORY)
    file(STRINGS "${manifest}" lines)
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "#.*" "" line "${line}")
      string(STRIP "${line}" line)
      if(line MATCHES "^set:(.*)")
        string(STRIP "${CMAKE_MATCH_1}" set_file)
        list(APPEND depends "${manifest_dir}/${set_file}")
      elseif(line MATCHES ":")
        # gamma:, current-weight:, color-map:, history-filter:, dilate-motion: (no variant name has a colon)
      elseif(line)
        list(APPEND variant_names "${line}")
      endif()
    endforeach()
  else()
    get_property(axis_set_dir GLOBAL PROPERTY KDOP_AXIS_SET_DIR)
    file(GLOB builtin_files "${axis_set_dir}/*.axes")
    set(builtin_sets)
    foreach(file IN LISTS builtin_files)
      get_filename_component(name "${file}" NAME_WE)
      list(APPEND builtin_sets ${name})
    endforeach()
    set(set_names)
    if(NOT ARG_SETS)
      set(set_names ${builtin_sets})
    endif()
    foreach(set IN LISTS ARG_SETS)
      if(set IN_LIST builtin_sets)
        list(APPEND arguments --sets ${set})
        list(APPEND set_names ${set})
      else()
        get_filename_component(path "${set}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
        if(NOT EXISTS "${path}")
          message(FATAL_ERROR "kdop_add_variants(${target}): '${set}' is not a built-in axis set (${builtin_sets}) and ${path} does not exist")
        endif()
        list(APPEND arguments --sets "${path}")
        list(APPEND depends "${path}")
        # The set's name is its `name:` line; reconfigure when the file changes, in case that did.
        file(STRINGS "${path}" name_line REGEX "^[ \t]*name:" LIMIT_COUNT 1)
        string(REGEX REPLACE "^[ \t]*name:[ \t]*([^ \t#]*).*" "\\1" name "${name_line}")
        list(APPEND set_names ${name})
        set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${path}")
      endif()
    endforeach()
    set(modes ${ARG_MODES})
    set(neighborhoods ${ARG_NEIGHBORHOODS})
    set(forms ${ARG_FORMS})
    foreach(mode IN LISTS modes)
      list(APPEND arguments --modes ${mode})
    endforeach()
    foreach(neighborhood IN LISTS neighborhoods)
      list(APPEND arguments --neighborhoods ${neighborhood})
    endforeach()
    foreach(form IN LISTS forms)
      list(APPEND arguments --forms ${form})
    endforeach()
    if(NOT modes)
      set(modes clip varclip)
    endif()
    if(NOT neighborhoods)
      set(neighborhoods n9 n5)
    endif()
    if(NOT forms)
      set(forms unrolled)
    endif()
    # <set>-<mode>-<neighborhood>[-loop], in kdop-gen's order.
    foreach(name IN LISTS set_names)
      foreach(mode IN LISTS modes)
        foreach(neighborhood IN LISTS neighborhoods)
          foreach(form IN LISTS forms)
            if(form STREQUAL "loop")
              list(APPEND variant_names "${name}-${mode}-${neighborhood}-loop")
            else()
              list(APPEND variant_names "${name}-${mode}-${neighborhood}")
            endif()
          endforeach()
        endforeach()
      endforeach()
    endforeach()
    if(ARG_BASELINES)
      list(APPEND arguments --baselines)
      list(APPEND variant_names gather-n9 gather-n5 copy)
    endif()
  endif()
  if(ARG_TARGET_ENV)
    list(APPEND arguments --target-env ${ARG_TARGET_ENV})
  endif()
  if(ARG_STRIP_NAMES)
    list(APPEND arguments --strip-names)
  endif()

  set(outputs "${header}" "${source}" "${json}")
  if(ARG_FUNCTIONS)
    set(function_dir "${out_dir}/functions")
    list(APPEND arguments --functions "${function_dir}")
    kdop_shader_language_extensions(extensions)
    foreach(name IN LISTS variant_names)
      foreach(extension IN LISTS extensions)
        list(APPEND outputs "${function_dir}/${name}.${extension}")
      endforeach()
    endforeach()
    set_property(TARGET ${target} PROPERTY KDOP_FUNCTION_DIR "${function_dir}")
    set(${target}_KDOP_FUNCTION_DIR "${function_dir}" PARENT_SCOPE)
  endif()
  set(depfile_arguments)
  if(ARG_SHADERS)
    set(shader_paths)
    foreach(shader IN LISTS ARG_SHADERS ARG_SHADER_INCLUDE_DIRS)
      # CMake writes the depfile it hands Ninja (cmake -E cmake_transform_depfile) without escaping
      # these, so Ninja would read another path and regenerate at every build.
      if(shader MATCHES "[$#\"]" OR shader MATCHES "\n")
        message(FATAL_ERROR "kdop_add_variants(${target}): '${shader}' holds '$', '#', a quote or a line break, which CMake's depfile for Ninja cannot carry (generation would rerun at every build); rename it")
      endif()
    endforeach()
    foreach(shader IN LISTS ARG_SHADERS)
      get_filename_component(path "${shader}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
      list(APPEND shader_paths "${path}")
      list(APPEND depends "${path}")
    endforeach()
    list(APPEND arguments --shaders ${shader_paths})
    if(ARG_HLSL_ENTRY)
      list(APPEND arguments --hlsl-entry ${ARG_HLSL_ENTRY})
    endif()
    foreach(dir IN LISTS ARG_SHADER_INCLUDE_DIRS)
      get_filename_component(path "${dir}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
      list(APPEND arguments --include-dirs "${path}")
    endforeach()
    # The files the shaders include are found while compiling; kdop-gen lists them in a depfile.
    set(depfile "${out_dir}/${header_stem}.d")
    list(APPEND arguments --depfile "${depfile}")
    set(depfile_arguments DEPFILE "${depfile}")
  endif()

  add_custom_command(
    OUTPUT ${outputs}
    COMMAND kdop::kdop-gen registry --header "${header}" --source "${source}" --namespace ${ARG_NAMESPACE}
            --json "${json}" ${arguments}
    DEPENDS ${depends} "$<TARGET_FILE:kdop::kdop-gen>"
    ${depfile_arguments}
    COMMENT "kdop: generating k-DOP variants for ${target}"
    VERBATIM)
  set(scope PRIVATE)
  if(ARG_PUBLIC)
    set(scope PUBLIC)
  endif()
  target_sources(${target} PRIVATE "${header}" "${source}")
  target_include_directories(${target} ${scope} "${out_dir}")
  set_property(TARGET ${target} PROPERTY KDOP_REFLECTION_JSON "${json}")
  set(${target}_KDOP_REFLECTION_JSON "${json}" PARENT_SCOPE)
  target_link_libraries(${target} ${scope} kdop::variant_headers)
endfunction()
