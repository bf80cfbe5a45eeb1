"""examples/cura/GcodeToolsFilter.py outside Cura: the plugin's own package
layout (a script in a subpackage beside Script.py) with stand-ins for Cura's
Script base class and UM's Logger and Message, fed Cura's chunks of a real
CuraEngine file. The filtered G-code must equal the tool's own output on the
same file, in Cura's chunk shape; a failing command leaves the chunks alone.
usage: cura_script.py SOURCE_DIR BIN_DIR"""
import os
import shutil
import subprocess
import sys
import tempfile

source, bin_dir = sys.argv[1], sys.argv[2]
root = tempfile.mkdtemp()
try:
    pkg = os.path.join(root, "PostProcessingPlugin")
    os.makedirs(os.path.join(pkg, "scripts"))
    os.makedirs(os.path.join(root, "UM"))
    open(os.path.join(pkg, "__init__.py"), "w").close()
    open(os.path.join(pkg, "scripts", "__init__.py"), "w").close()
    with open(os.path.join(pkg, "Script.py"), "w") as f:
        f.write("class Script:\n"
                "    settings = {}\n"
                "    def getSettingValueByKey(self, key):\n"
                "        return self.settings[key]\n")
    open(os.path.join(root, "UM", "__init__.py"), "w").close()
    with open(os.path.join(root, "UM", "Logger.py"), "w") as f:
        f.write("class Logger:\n    logged = []\n"
                "    @staticmethod\n    def log(level, text, *args):\n        Logger.logged.append(text % args)\n")
    with open(os.path.join(root, "UM", "Message.py"), "w") as f:
        f.write("class Message:\n    shown = []\n"
                "    def __init__(self, text, title):\n        self.text = text\n"
                "    def show(self):\n        Message.shown.append(self.text)\n")
    shutil.copy(os.path.join(source, "examples", "cura", "GcodeToolsFilter.py"), os.path.join(pkg, "scripts"))
    sys.path.insert(0, root)
    from PostProcessingPlugin.scripts.GcodeToolsFilter import GcodeToolsFilter, split_layers
    from UM.Message import Message

    with open(os.path.join(source, "tests", "fixtures", "cura_cube_0.2_abs_zhop_skirt.gcode")) as f:
        gcode = f.read()
    data = split_layers(gcode)
    assert "".join(data) == gcode, "splitting loses nothing"
    assert len(data) > 50 and all(c.startswith(";LAYER:") for c in data[1:]), "one chunk per layer"

    tool = os.path.join(bin_dir, "gc-pause-at")
    args = ["--before-layer", "12", "--method", "M600", "--bed", "220x220"]
    script = GcodeToolsFilter()
    import json
    assert json.loads(script.getSettingDataString())["settings"]["command"]["type"] == "str"
    script.settings = {"command": " ".join([tool] + args)}
    out = script.execute(list(data))
    expected = subprocess.run([tool] + args, input=gcode.encode(), stdout=subprocess.PIPE, check=True).stdout.decode()
    assert "".join(out) == expected, "the chunks join to the tool's own output"
    assert expected != gcode and expected.count("\nM600\n") == 1
    assert len(out) == len(data), "the same layers, chunk for chunk"

    script.settings = {"command": tool + " --before-layer 5000 --bed 220x220"}
    kept = script.execute(list(data))
    assert kept == data, "a failing command changes nothing"
    assert len(Message.shown) == 1 and "gc-pause-at" in Message.shown[0], Message.shown
    print("cura script: 9 checks passed")
finally:
    shutil.rmtree(root)
