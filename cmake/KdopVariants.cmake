# kdop_add_variants(<target>
#     [SETS <name-or-path>...]          built-in set names (the stems of shader_templates/axis_sets/*.axes:
#                                       aabb ycocg dop16-asphalt dop16-grass dop22 dop32) or paths to .axes
#                                       files; default: every built-in set
#     [MODES <clip|varclip>...]         default: both
#     [NEIGHBORHOODS <n9|n5>...]        default: both
#     [FORMS <unrolled|loop>...]        default: unrolled; loop is the supplement's form, a baseline
#     [BASELINES]                       also the cost baselines gather-n9, gather-n5 and copy
#     [NAMESPACE <ns>]                  C++ namespace of the registry; default: <target> made an identifier
#     [HEADER <file-name>]              default: <target>_kdop_variants.h
#     [PUBLIC])                         also give <target>'s users the header (for a library target)
#
# Generates, at build time, a header and source holding the variants' optimized SPIR-V and their
# registry (see core/include/kdop/variant.h), adds them to <target>, and lets <target>
# include the header by its file name. Generation reruns when a user axis file or kdop-gen (which
# embeds the built-in sets and templates) changes, and at no other time.
include_guard(GLOBAL)

# The built-in sets are the axis files kdop-gen embeds; the list is read from that folder, not kept
# here, and inside the function, so it holds wherever kdop_add_variants() is called from. An
# installed package's config file names the installed copy first; in kdop's own tree it is here.
get_property(kdop_axis_set_dir_known GLOBAL PROPERTY KDOP_AXIS_SET_DIR SET)
if(NOT kdop_axis_set_dir_known)
  set_property(GLOBAL PROPERTY KDOP_AXIS_SET_DIR "${CMAKE_CURRENT_LIST_DIR}/../shader_templates/axis_sets")
endif()

function(kdop_add_variants target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "PUBLIC;BASELINES" "NAMESPACE;HEADER" "SETS;MODES;NEIGHBORHOODS;FORMS")
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

  get_property(axis_set_dir GLOBAL PROPERTY KDOP_AXIS_SET_DIR)
  file(GLOB builtin_files "${axis_set_dir}/*.axes")
  set(builtin_sets)
  foreach(file IN LISTS builtin_files)
    get_filename_component(name "${file}" NAME_WE)
    list(APPEND builtin_sets ${name})
  endforeach()

  # User axis files are inputs of their own; built-in sets live inside kdop-gen.
  set(arguments)
  set(depends kdop::kdop-gen)
  foreach(set IN LISTS ARG_SETS)
    if(set IN_LIST builtin_sets)
      list(APPEND arguments --sets ${set})
    else()
      get_filename_component(path "${set}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
      if(NOT EXISTS "${path}")
        message(FATAL_ERROR "kdop_add_variants(${target}): '${set}' is not a built-in axis set (${builtin_sets}) and ${path} does not exist")
      endif()
      list(APPEND arguments --sets "${path}")
      list(APPEND depends "${path}")
    endif()
  endforeach()
  foreach(mode IN LISTS ARG_MODES)
    list(APPEND arguments --modes ${mode})
  endforeach()
  foreach(neighborhood IN LISTS ARG_NEIGHBORHOODS)
    list(APPEND arguments --neighborhoods ${neighborhood})
  endforeach()
  foreach(form IN LISTS ARG_FORMS)
    list(APPEND arguments --forms ${form})
  endforeach()
  if(ARG_BASELINES)
    list(APPEND arguments --baselines)
  endif()

  add_custom_command(
    OUTPUT "${header}" "${source}"
    COMMAND kdop::kdop-gen registry --header "${header}" --source "${source}" --namespace ${ARG_NAMESPACE} ${arguments}
    DEPENDS ${depends} "$<TARGET_FILE:kdop::kdop-gen>"
    COMMENT "kdop: generating k-DOP variants for ${target}"
    VERBATIM)
  set(scope PRIVATE)
  if(ARG_PUBLIC)
    set(scope PUBLIC)
  endif()
  target_sources(${target} PRIVATE "${header}" "${source}")
  target_include_directories(${target} ${scope} "${out_dir}")
  target_link_libraries(${target} ${scope} kdop::variant_headers)
endfunction()
