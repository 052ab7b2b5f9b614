"""External spreadsheet engines used to cross-check workbooks (LibreOffice headless)."""
