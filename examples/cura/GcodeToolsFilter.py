# Cura "Post Processing" script: pipes the sliced G-code through a gcode-tools
# command line (README.md beside it says where to put it). Cura 4.x and 5.x.
#
# Cura hands a script its G-code as a list of text chunks (the header and
# start code, then one chunk per ";LAYER:n", then the end code); this joins
# them, runs the command with the G-code on standard input, and splits the
# output again at each ";LAYER:" line. A command that fails leaves Cura's
# G-code as it was and says why in a message (and in cura.log).
import json
import shlex
import subprocess

from ..Script import Script


def split_layers(text):
    """The chunks of `text`: what comes before the first ;LAYER: line, then one per layer."""
    chunks, current = [], []
    for line in text.splitlines(keepends=True):
        if line.startswith(";LAYER:") and current:
            chunks.append("".join(current))
            current = []
        current.append(line)
    if current:
        chunks.append("".join(current))
    return chunks


def pipe_through(command, data):
    """Cura's chunks after `command` (a shell-style command line, run without a shell)."""
    result = subprocess.run(shlex.split(command), input="".join(data).encode(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, check=False)
    if result.returncode != 0:
        raise RuntimeError("'%s' failed (exit %d): %s"
                           % (command, result.returncode, result.stderr.decode(errors="replace").strip()))
    return split_layers(result.stdout.decode())


class GcodeToolsFilter(Script):
    def getSettingDataString(self):
        return json.dumps({
            "name": "gcode-tools filter",
            "key": "GcodeToolsFilter",
            "metadata": {},
            "version": 2,
            "settings": {
                "command": {
                    "label": "Command",
                    "description": "A gc tool and its options; it reads the G-code on standard input "
                                   "(the bed is not in Cura's G-code: give --bed where a tool needs it)",
                    "type": "str",
                    "default_value": "gc-pause-at --before-layer 12 --method M600 --bed 220x220",
                },
            },
        })

    def execute(self, data):
        command = self.getSettingValueByKey("command")
        try:
            return pipe_through(command, data)
        except (OSError, RuntimeError) as error:
            from UM.Logger import Logger
            from UM.Message import Message
            Logger.log("e", "gcode-tools: %s", error)
            Message(text=str(error), title="gcode-tools filter").show()
            return data
