"""The workbook writer (XlsxWriter): Table, Parameters, Checks, Summary, Charts, About."""

from .writer import output_path, write_workbook

__all__ = ["output_path", "write_workbook"]
