"""The result store of a validation folder: what survives crashes, concurrent writers and
interruptions, for every command that writes into ``--out``.

* :mod:`.files` -- the folder lock (:class:`FolderLock`), atomic writes, the row checksum
  (:class:`RowDigest`) and the resume state of one run (:func:`save_state`,
  :func:`load_state`);
* :mod:`.case_files` -- the CSVs of a validation case, its manifest and the resume plan
  that keeps only what verifies;
* :mod:`.rows` -- the files of the studies: :class:`StudyStore` (settings checked, resumed
  unit by unit, each file rewritten atomically, the table last), :func:`read_rows`,
  and :func:`command_lock`, the lock of a command that writes a
  folder;
* :mod:`.tables` -- :class:`TableWriter`, a measured table of
  :data:`validation.data.registry.TABLES` held under its lock and written row by row.
"""

from .case_files import (CaseFiles, append_csv_rows, case_manifest, resume_plan, spec_sig,
                         state_path)
from .rows import (DamagedFileError, StudyStore,
                   command_lock, read_rows)
from .tables import TableWriter
from .files import (STATE_VERSION, FolderLock, LockedError, RowDigest, aside_path,
                    csv_line, dumps, keep_aside, load_state, read_npz, regular_file,
                    save_point, save_points, save_state, saved_point, saved_points,
                    write_csv_atomic, write_npz_atomic, write_text_atomic)

__all__ = [
    "LockedError", "FolderLock", "write_text_atomic", "write_csv_atomic", "write_npz_atomic",
    "csv_line", "regular_file", "aside_path", "keep_aside", "read_npz",
    "RowDigest", "save_state", "load_state", "save_point", "saved_point", "save_points",
    "saved_points", "dumps",
    "STATE_VERSION",
    "CaseFiles", "append_csv_rows", "case_manifest", "resume_plan", "spec_sig", "state_path",
    "command_lock", "read_rows", "DamagedFileError", "StudyStore",
    "TableWriter",
]
