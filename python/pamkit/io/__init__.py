"""Files in and out: experiment files (TOML and CSV, one reader and one writer), tensile machines'
exports (Instron Bluehill, ZwickRoell testXpert) and the Arduino logger's host side."""
