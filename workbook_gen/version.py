"""The generator's version, written into every workbook's About sheet."""

VERSION = "0.1.0"
