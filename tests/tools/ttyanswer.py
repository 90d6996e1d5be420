#!/usr/bin/python3
"""ttyanswer.py: run a command with a pseudo-terminal of its own as its controlling terminal
(/dev/tty), its standard input, output and error left as they are, and answer the questions it
asks there: each time TEXT appears on the terminal, ANSWER is typed (Python escapes: '\\n' is
Enter). Everything the command wrote to the terminal goes to --log. Bounded: past --timeout
seconds the command is killed and the exit status is 124; otherwise it is the command's (128 + N
for a signal).

  ttyanswer.py [--timeout S] [--log FILE] [--answer TEXT=ANSWER]... -- CMD ARGS...

The answers are used in order, one per question; a question after the last answer gets none
(the command then waits for its own bound)."""
import os
import select
import signal
import sys
import time


def main(argv):
    timeout, log, answers = 60.0, None, []
    i = 1
    while i < len(argv) and argv[i] != '--':
        a = argv[i]
        if a == '--timeout':
            timeout = float(argv[i + 1]); i += 2
        elif a == '--log':
            log = argv[i + 1]; i += 2
        elif a == '--answer':
            text, _, ans = argv[i + 1].partition('=')
            answers.append((text.encode(), ans.encode().decode('unicode_escape').encode()))
            i += 2
        else:
            sys.stderr.write('ttyanswer.py: unknown option %s\n' % a)
            return 64
    cmd = argv[i + 1:]
    if not cmd:
        sys.stderr.write(__doc__)
        return 64
    master, slave = os.openpty()
    pid = os.fork()
    if pid == 0:
        try:
            os.close(master)
            os.setsid()
            name = os.ttyname(slave)
            os.close(slave)
            fd = os.open(name, os.O_RDWR)   # a session leader's first terminal: its controlling one
            os.close(fd)
            os.execvp(cmd[0], cmd)
        except OSError as e:
            sys.stderr.write('ttyanswer.py: %s: %s\n' % (cmd[0], e))
        os._exit(127)
    os.close(slave)
    seen, end, status = b'', time.monotonic() + timeout, None
    while status is None:
        left = end - time.monotonic()
        if left <= 0:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            status = 124
            break
        r, _, _ = select.select([master], [], [], min(left, 0.1))
        if r:
            try:
                data = os.read(master, 4096)
            except OSError:
                data = b''
            seen += data
            while answers and answers[0][0] in seen:
                text, ans = answers.pop(0)
                cut = seen.index(text) + len(text)
                if log:
                    with open(log, 'ab') as f:
                        f.write(seen[:cut] + b'[typed ' + repr(ans).encode() + b']\n')
                seen = seen[cut:]
                os.write(master, ans)
        w, st = os.waitpid(pid, os.WNOHANG)
        if w:
            status = os.waitstatus_to_exitcode(st)
            status = 128 - status if status < 0 else status
    if log:
        with open(log, 'ab') as f:
            f.write(seen)
    os.close(master)
    return status


if __name__ == '__main__':
    sys.exit(main(sys.argv))
