/* test_tr_errno.c: a transport's failure carries its errno (io_errno), so that programs decide
 * 70, 74 or 75 by value and not by the words of the message; and which names are device links. */
#include <errno.h>
#include <stdlib.h>
#include "io/transport.h"
#include "unit.h"

int main(void)
{
	char err[600];
	io_transport_t *t = io_open_write("/dev/full", err, sizeof err);
	CHECK(t != NULL, "/dev/full opened in place: %s", t ? "" : err);
	if (t) {
		CHECK(io_errno(t) == 0, "no failure, no errno");
		int rc = io_write(t, "abc", 3) || io_flush(t);
		CHECK(rc && io_errno(t) == ENOSPC && !io_temporary(t), "a full device: ENOSPC by value (%s)", io_error(t));
		io_close(t, IO_ABORT);
	}
	errno = 0;
	t = io_open_write("/nonexistent-dir/x/out.png", err, sizeof err);
	CHECK(!t && errno != 0 && errno != ENOMEM, "a path that cannot be made: errno %d, not out of memory (%s)", errno, err);
	errno = 0;
	t = io_open_write("serial:/nonexistent/ttyUSB9", err, sizeof err);
	CHECK(!t && errno == EIO, "an absent device link: EIO (%s)", err);
	CHECK(io_is_link_name("serial:/dev/ttyUSB0") && io_is_link_name("tcp:h") && io_is_link_name("usb:any")
		&& io_is_link_name("hid:10c4:ea80"), "serial: tcp: usb: hid: are device links");
	CHECK(!io_is_link_name("out.hpgl") && !io_is_link_name("-") && !io_is_link_name("fb:/dev/fb0"),
		"files, standard output and fb: are not");
	return UNIT_DONE();
}
