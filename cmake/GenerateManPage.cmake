# Writes the manual page of one program with help2man, from its own --help (cmake -P, from ArchipelagoInstall.cmake).
#   -DHELP2MAN=<help2man> -DPROGRAM=<executable> -DNAME=<name in the page> -DSUMMARY=<one line>
#   -DVERSION=<version> -DOUTPUT=<page.1> [-DCOMMANDS=ON]
# COMMANDS=ON: the program has subcommands (archipelago-cli): each one's --help becomes a subsection of a COMMANDS
# section, so that `man archipelago-cli` holds every option of every command.
# Nothing here is written by hand: the pages follow the programs' options as they change.
cmake_minimum_required(VERSION 3.21)

# Text as a roff no-fill block: backslashes escaped, lines starting with . or ' (roff requests) or [ (a section
# of help2man's include file) protected.
function(_roff_block text out)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'[])" "\\1\\\\&\\2" text "${text}")
  set(${out} ".nf\n${text}\n.fi\n" PARENT_SCOPE)
endfunction()

# The program is run by its name, found on PATH, so that its usage lines name it and not its build path.
get_filename_component(program_dir "${PROGRAM}" DIRECTORY)
get_filename_component(program_name "${PROGRAM}" NAME)
set(ENV{PATH} "${program_dir}:$ENV{PATH}")
set(include "${OUTPUT}.include")
set(sections "[SEE ALSO]\nThe README and docs/ of the Archipelago sources; C. F. F. Karney, Long-time \
correlations in the stochastic regime, Physica D 8 (1983) 360\\(en380.\n")
if(COMMANDS)
  execute_process(COMMAND "${program_name}" --help OUTPUT_VARIABLE help RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${PROGRAM} --help failed (${status})")
  endif()
  # CLI11's "Subcommands:" list: two spaces, the name, spaces, its summary.
  string(REGEX REPLACE ".*\nSubcommands:\n" "" list "${help}")
  string(REGEX MATCHALL "(^|\n)  [a-z][a-z0-9-]*" names "${list}")
  string(APPEND sections "\n[COMMANDS]\nEach command's options, as `${NAME} COMMAND --help` prints them.\n")
  foreach(name IN LISTS names)
    string(STRIP "${name}" name)
    execute_process(COMMAND "${program_name}" ${name} --help OUTPUT_VARIABLE sub RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "${PROGRAM} ${name} --help failed (${status})")
    endif()
    _roff_block("${sub}" block)
    string(APPEND sections ".SS ${name}\n${block}")
  endforeach()
endif()
file(WRITE "${include}" "${sections}")
# --locale: the programs print UTF-8 (x², √K, N⁻¹), which help2man turns into ? in its default C locale.
execute_process(COMMAND "${HELP2MAN}" --no-info --no-discard-stderr --locale=C.UTF-8 "--name=${SUMMARY}"
                        "--version-string=${VERSION}" "--include=${include}" "--output=${OUTPUT}" "${program_name}"
                RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "help2man ${PROGRAM}: ${err}")
endif()
file(REMOVE "${include}")
