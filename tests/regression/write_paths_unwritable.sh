#!/usr/bin/env bash
# An output's folder must exist and be writable; the message gives the system's reason (exit 2,
# the key named, nothing written):
#  - output.file in /proc/self, a folder not even root may write into;
#  - output.history_file below a regular file ("Not a directory");
#  - as a user other than root: a folder without write permission, and a read-only existing
#    output ("Permission denied"). Root passes every permission check (access(W_OK)), so this
#    part runs only for other users.
# usage: write_paths_unwritable.sh PERIFEM SCRATCH   (from the tests/ folder)
source common/write_paths_env.sh
pd_deck "output: {file: /proc/self/out.e}" > proc.yaml && refused proc.yaml file "cannot write into the folder '/proc/self'"
touch plain_file
pd_deck "output: {history_file: plain_file/h.h5}" > notdir.yaml && refused notdir.yaml history_file "Not a directory"
if [ "$(id -u)" != 0 ]; then
  mkdir locked && chmod 555 locked
  pd_deck "output: {file: locked/out.e}" > locked.yaml && refused locked.yaml file "Permission denied"
  touch ro.e && chmod 444 ro.e
  pd_deck "output: {file: ro.e}" > ro.yaml && refused ro.yaml file "Permission denied"
  chmod 755 locked
else
  echo "(root: folders and files without write permission are writable; those cases are not run)"
fi
exit $fail
