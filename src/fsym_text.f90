!> Allocation-free building of messages in a fixed-length buffer (a failing step must not
!> allocate to say why: an internal write or a concatenation of allocatable results does).
module fsym_text
    use fsym_kinds, only: ik
    implicit none
    private

    public :: fsym_text_put, fsym_text_put_int

contains

    !> Append `s` to buf(1:pos) (cut at the end of buf); pos is updated.
    pure subroutine fsym_text_put(buf, pos, s)
        character(len=*), intent(inout) :: buf   !! the buffer
        integer, intent(inout) :: pos            !! characters used so far
        character(len=*), intent(in) :: s        !! text to append
        integer :: m
        m = max(0, min(len(s), len(buf) - pos))
        buf(pos + 1:pos + m) = s(1:m)
        pos = pos + m
    end subroutine fsym_text_put

    !> Append the decimal digits of k to buf(1:pos); pos is updated.
    pure subroutine fsym_text_put_int(buf, pos, k)
        character(len=*), intent(inout) :: buf   !! the buffer
        integer, intent(inout) :: pos            !! characters used so far
        integer(ik), intent(in) :: k             !! the integer
        character(len=20) :: d
        integer(ik) :: x
        integer :: n
        n = len(d); x = abs(k)
        do
            d(n:n) = achar(iachar('0') + int(abs(mod(x, 10_ik))))
            x = x / 10
            if (x == 0) exit
            n = n - 1
        end do
        if (k < 0) call fsym_text_put(buf, pos, '-')
        call fsym_text_put(buf, pos, d(n:))
    end subroutine fsym_text_put_int

end module fsym_text
