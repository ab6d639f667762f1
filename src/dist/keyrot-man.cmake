# Writes keyrot's man page from the program's own help, so that the two are
# never written twice: a section per command (its --help, which ends with
# examples), the formats (keyrot help formats), and the examples gathered.
#   cmake -DKEYROT=path/to/keyrot -DOUT=keyrot.1 -DVERSION=0.1.0 -P keyrot-man.cmake

# The output of `keyrot ARGS...` in `var`.
function(keyrot_help var)
  execute_process(COMMAND ${KEYROT} ${ARGN} OUTPUT_VARIABLE text RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "keyrot ${ARGN} failed (${status})")
  endif()
  set(${var} "${text}" PARENT_SCOPE)
endfunction()

# `text` as roff, line for line: backslashes and minus signs escaped (a
# flag reads as typed), and a line that would start with a request made plain.
function(roff var text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  string(REGEX REPLACE "\n([.'])" "\n\\\\&\\1" text "\n${text}")
  string(SUBSTRING "${text}" 1 -1 text)
  set(${var} "${text}" PARENT_SCOPE)
endfunction()

# `text` set as it is, in a fixed layout.
function(verbatim var text)
  roff(text "${text}")
  set(${var} ".PP\n.nf\n${text}.fi\n" PARENT_SCOPE)
endfunction()

keyrot_help(main --help)
string(REGEX MATCH "Subcommands:\n([^\n]+\n)+" listed "${main}")
string(REGEX MATCHALL "\n  [a-z]+" commands "${listed}")
string(REGEX REPLACE "\n  " "" commands "${commands}")
list(REMOVE_ITEM commands help)
if(NOT commands)
  message(FATAL_ERROR "no commands in keyrot --help")
endif()

set(page ".TH KEYROT 1 \"\" \"keyrot ${VERSION}\" \"User Commands\"\n")
string(APPEND page ".SH NAME\nkeyrot \\- keyframe rotation interpolator\n")
string(APPEND page ".SH SYNOPSIS\n")
foreach(command IN LISTS commands)
  string(APPEND page ".B keyrot ${command}\n[\\fIOPTIONS\\fR]\n.br\n")
endforeach()
string(APPEND page ".B keyrot help\n[\\fICOMMAND\\fR | \\fBformats\\fR]\n")
verbatim(text "${main}")
string(APPEND page ".SH DESCRIPTION\n${text}")

string(APPEND page ".SH COMMANDS\n")
set(examples "")
foreach(command IN LISTS commands)
  keyrot_help(help ${command} --help)
  verbatim(text "${help}")
  string(APPEND page ".SS ${command}\n${text}")
  string(REGEX MATCH "Examples:\n.*" shown "${help}")
  string(REGEX REPLACE "^Examples:\n" "" shown "${shown}")
  string(APPEND examples "${shown}")
endforeach()

keyrot_help(formats help formats)
verbatim(text "${formats}")
string(APPEND page ".SH FORMATS\n${text}")
verbatim(text "${examples}")
string(APPEND page ".SH EXAMPLES\n${text}")
string(APPEND page ".SH SEE ALSO\n\\fBkeyrot help formats\\fR, and docs/guide.md of the keyrot sources.\n")
file(WRITE "${OUT}" "${page}")
