"""The workbook writer (XlsxWriter): Table, Parameters, Checks, Summary, Charts, About."""

from .writer import output_path, workbook_bytes, write_workbook

__all__ = ["output_path", "workbook_bytes", "write_workbook"]
