# An animation re-run into the same folder (issue 13): `cmake -DTOOL=<mpr-render> -DDIR=<folder>
# -P animation_rerun.cmake`. A stand-in `ffmpeg` (a shell script on PATH that records its
# arguments and creates the MP4) shows what mpr-render asks of ffmpeg:
#   1. 3 frames at --fps 5: frames 1-3, ffmpeg told -framerate 5 and -frames:v 3;
#   2. 2 frames into the same name: frame 3 of run 1 removed, ffmpeg told -frames:v 2;
#   3. no ffmpeg on PATH: one line saying the MP4 was skipped, exit 0.
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}/bin" "${DIR}/empty" "${DIR}/anim")
file(WRITE "${DIR}/bin/ffmpeg" "#!/bin/sh\nprintf '%s\\n' \"$@\" > \"${DIR}/ffmpeg_args.txt\"\nfor a; do last=\"$a\"; done\n: > \"$last\"\n")
file(CHMOD "${DIR}/bin/ffmpeg" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
set(_out "${DIR}/anim/a.png")

function(run_tool path_value)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PATH=${path_value}" "${TOOL}" ${ARGN} --size 8x6 --output "${_out}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  message("$ mpr-render ${ARGN}\n${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "exit status ${rc}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_args)
  file(READ "${DIR}/ffmpeg_args.txt" args)
  string(REPLACE "\n" " " args "${args}")
  foreach(want IN LISTS ARGN)
    if(NOT args MATCHES "${want}")
      message(FATAL_ERROR "ffmpeg arguments '${args}' lack '${want}'")
    endif()
  endforeach()
endfunction()

run_tool("${DIR}/bin:$ENV{PATH}" --tilt-x 0:10 --frames 3 --fps 5)
foreach(i 1 2 3)
  if(NOT EXISTS "${DIR}/anim/a_000${i}.png")
    message(FATAL_ERROR "a_000${i}.png not written")
  endif()
endforeach()
expect_args("-framerate 5 " "a_%04d.png" "-frames:v 3 " "a.mp4")

run_tool("${DIR}/bin:$ENV{PATH}" --tilt-x 0:10 --frames 2)
if(EXISTS "${DIR}/anim/a_0003.png")
  message(FATAL_ERROR "a_0003.png of the first run is still there")
endif()
if(NOT out MATCHES "removed 1 stale frame of an earlier run \\(a_0003.png onwards\\)")
  message(FATAL_ERROR "no message about the stale frame")
endif()
expect_args("-framerate 12 " "-frames:v 2 ")

file(REMOVE "${DIR}/anim/a.mp4")
run_tool("${DIR}/empty" --tilt-x 0:10 --frames 2)
# stderr is not a terminal here: one progress line a frame, then one line saying the MP4 was skipped.
if(NOT err MATCHES "^(frame [0-9] of 2 rendered [^\n]*\n)+mpr-render: skipped [^\n]*a.mp4: ffmpeg is not on PATH[^\n]*\n$")
  message(FATAL_ERROR "expected the progress lines and one line saying the MP4 was skipped")
endif()
if(EXISTS "${DIR}/anim/a.mp4")
  message(FATAL_ERROR "a.mp4 written without ffmpeg")
endif()
message("animation re-run: ok")
